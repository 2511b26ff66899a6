/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "bench_command_line.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace pcl::phaser {
namespace bench {

namespace {

/** The options several subcommands take, spelled and documented once. */
const BenchOption kSharedOptions[] = {
    {"--data", "DIR",
     "the shared data directory (default " PCL_PHASER_DEFAULT_DATA_DIR ")"},
    {"--pairs-file", "F",
     "the pairs (default <data>/lidar/balm_handheld/pairs.txt); scans are read from "
     "its folder unless their names are absolute"},
    {"--max-pairs", "N", "only the first N pairs (default 0: all)"},
    {"--methods", "A,B",
     "phaser,phaser_xyz,phaser_plain,sacia,prerejective,fpcs,kfpcs,icp,gicp,ndt"},
    {"--seed", "S", "seed of poses, perturbations and PCL's RANSAC (default 1)"},
    {"--voxel", "V", "leaf (m) of PCL's methods' downsampling"},
    {"--fpcs-time", "S", "time limit of FPCS/KFPCS in seconds (default 10)"},
    {"--csv", "FILE", "every trial as CSV"},
    {"--md", "FILE", "the markdown summary (default: stdout)"},
    {"--plots", "DIR", "plots (gnuplot .dat/.gp, PNG when gnuplot is installed)"},
    {"--reference-drift", "DX,DY,DZ",
     "remove a linear drift of the odometry (world frame, m per scan index: scan i's "
     "position - i x drift) from the reference poses"},
};

} // namespace

BenchOption sharedOption(const char* name, const char* help)
{
  for (const BenchOption& o : kSharedOptions)
    if (!std::strcmp(o.name, name))
      return {o.name, o.value, help ? help : o.help};
  std::fprintf(stderr, "pcl_phaser_bench: no shared option %s\n", name);
  std::abort();
}

BenchArguments::BenchArguments(int argc, char** argv, const Subcommand& sub,
                               std::string command)
    : sub_(sub)
    , command_(std::move(command))
{
  std::set<std::string> switches, valued;
  for (const BenchOption& o : sub.options)
    (o.value ? valued : switches).insert(o.name);
  error_ = collectArguments(argc, argv, switches, valued, line_, sub.engine);
  if (error_.empty() && !sub.files && !line_.files.empty())
    error_ = "Unexpected argument '" + line_.files.front() + "'";
}

std::string BenchArguments::text(const char* name, const std::string& fallback) const
{
  std::string value;
  return line_.value(name, value) ? value : fallback;
}

long BenchArguments::integer(const char* name, long fallback)
{
  long v = fallback;
  if (has(name))
    check(parseInteger(text(name), -(1L << 40), 1L << 40, v),
          "Invalid value '" + text(name) + "' for " + name + ": expected an integer");
  return v;
}

double BenchArguments::number(const char* name, double fallback)
{
  double v = fallback;
  if (has(name))
    check(parseNumber(text(name), v),
          "Invalid value '" + text(name) + "' for " + name + ": expected a number");
  return v;
}

std::vector<std::string> BenchArguments::list(const char* name,
                                              std::vector<std::string> fallback) const
{
  if (!has(name))
    return fallback;
  std::vector<std::string> parts;
  std::stringstream in(text(name));
  for (std::string part; std::getline(in, part, ',');)
    if (!part.empty())
      parts.push_back(part);
  return parts;
}

std::vector<double> BenchArguments::numbers(const char* name,
                                            std::vector<double> fallback)
{
  std::vector<double> out;
  for (const std::string& item : list(name, {})) {
    double v = 0.0;
    if (!check(parseNumber(item, v), "Invalid value '" + text(name) + "' for " + name +
                                         ": expected comma-separated numbers"))
      return fallback;
    out.push_back(v);
  }
  return has(name) ? out : fallback;
}

PhaserParameters BenchArguments::engine(int threads)
{
  PhaserParameters p;
  p.num_threads = threads;
  const std::string problem = setEngineOptions(line_.engine, p);
  check(problem.empty(), problem);
  return p;
}

bool BenchArguments::check(bool ok, const std::string& message)
{
  if (!ok && error_.empty())
    error_ = message;
  return ok;
}

int BenchArguments::fail() const
{
  std::fprintf(stderr, "pcl_phaser_bench %s: %s (see pcl_phaser_bench %s --help)\n",
               sub_.name, error_.c_str(), sub_.name);
  return 2;
}

void printSubcommandHelp(const Subcommand& sub)
{
  PhaserParameters defaults;
  defaults.num_threads = sub.threads;
  std::printf("Usage: pcl_phaser_bench %s [options]%s%s\n  %s\n\nOptions:\n", sub.name,
              sub.files ? " " : "", sub.files ? sub.files : "", sub.summary);
  for (const BenchOption& o : sub.options) {
    const std::string name =
        std::string(o.name) + (o.value ? " " : "") + (o.value ? o.value : "");
    const char* gap = name.size() > 19 ? "\n                       " : "";
    std::printf("    %-19s%s = %s\n", name.c_str(), gap, o.help);
  }
  std::printf("    %-19s = this help\n", "-h, --help");
  if (sub.engine)
    std::printf("\nEngine settings (pcl_phaser's, as pcl_phaser_align takes them):\n%s",
                engineOptionsHelp(defaults).c_str());
}

} // namespace bench
} // namespace pcl::phaser
