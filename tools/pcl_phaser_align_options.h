// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file pcl_phaser_align_options.h
 * \brief The command line of `pcl_phaser_align`: exit codes, defaults, the Options
 * and their parsing (the engine's options: engine_options.h). Every problem is
 * reported with print_error() and turned into an exit code, never an exception.
 */
#pragma once

#include "cloud_reading.h"
#include "engine_options.h"
#include "pcl_phaser_align_screenshot.h"

#include <pcl/console/print.h>

#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string>
#include <strings.h>
#include <vector>

namespace pcl {
namespace phaser {
namespace align_tool {

using namespace pcl::console;

/** \brief Exit codes (also listed by printHelp()). */
enum ExitCode {
  kOk = 0,
  kUsage = 1,        ///< bad command line or option value
  kInput = 2,        ///< an input file (cloud or --gt) is missing, unreadable or unfit
  kNotConverged = 3, ///< PHASER, or ICP with -icp, did not converge
  kDemoMissed = 4,   ///< the demo converged but missed its accuracy bounds
  kOutput = 5        ///< -o, -m or --screenshot could not be written
};

const int default_demo_threads = 2;
const int default_seed = 1;
const double default_icp_distance = 1.0; // meters
const int default_width = 1024, default_height = 768;
const char* const default_demo_overlay = "phaser_demo_overlay.pcd";
// The demo passes when the global stage and ICP are this close to the truth (seed 1's
// figures: doc/benchmarks.md, *The embedded demo*).
const double demo_rre_deg = 1.0, demo_rte_m = 0.2;
const double demo_icp_rre_deg = 0.1, demo_icp_rte_m = 0.02;

struct Options {
  std::string source, target, output, overlay, screenshot, gt;
  bool demo = false, icp = false, icp_point = false, json = false;
  double icp_distance = default_icp_distance;
  pcl::phaser::PhaserParameters params; ///< the engine's (the demo: 2 threads)
  pcl::phaser::CommandLine line;        ///< the options and files given
  std::string error;                    ///< the message of the problem found
  int width = default_width, height = default_height, seed = default_seed;
};

/** \brief print_error() a printf-style message, keep it in \a message (the JSON
 *  object's "error"), return \a code. */
inline int fail(std::string& message, int code, const char* format, ...)
{
  char buffer[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof(buffer), format, args);
  va_end(args);
  message = buffer;
  std::fflush(stdout); // keep the message after what was printed before it
  print_error("%s\n", buffer);
  return (code);
}

inline bool hasExtension(const std::string& path, const char* ext)
{
  const std::size_t n = std::strlen(ext);
  return (path.size() > n && !strcasecmp(path.c_str() + path.size() - n, ext));
}

/** \brief Collect the file arguments (SOURCE TARGET) and set the switches (--demo,
 * -icp, --icp-point, --json); rejects unknown options, options without their value
 * and a wrong number of files.
 * \return kOk or kUsage (after fail()) */
inline int parseFilesAndSwitches(int argc, char** argv, Options& opt)
{
  static const std::set<std::string> switches = {
      "-icp", "--icp", "--icp-point", "--json", "--demo", "--print-parameters",
      "-h",   "--help"};
  static const std::set<std::string> valued = {
      "--icp-dist", "-o", "-m", "--size", "--screenshot", "--gt", "--seed"};
  const std::string error =
      pcl::phaser::collectArguments(argc, argv, switches, valued, opt.line);
  if (!error.empty())
    return (fail(opt.error, kUsage, "%s (see -h).", error.c_str()));
  const std::vector<std::string>& files = opt.line.files;
  opt.demo = argc == 1 || opt.line.count("--demo");
  opt.icp = opt.demo || opt.line.count("-icp") || opt.line.count("--icp");
  opt.icp_point = opt.line.count("--icp-point");
  opt.json = opt.line.count("--json");
  if (opt.demo && !files.empty())
    return (fail(opt.error, kUsage, "--demo takes no SOURCE/TARGET files."));
  if (!opt.demo && files.size() < 2)
    return (fail(opt.error, kUsage,
                 "Missing %s: the syntax is SOURCE TARGET [options] (see -h).",
                 files.empty() ? "SOURCE and TARGET" : "the TARGET argument"));
  if (!opt.demo && files.size() > 2)
    return (fail(opt.error, kUsage,
                 "Too many file arguments ('%s'): expected SOURCE TARGET.",
                 files[2].c_str()));
  if (!opt.demo) {
    opt.source = files[0];
    opt.target = files[1];
  }
  return (kOk);
}

/** \brief The engine options into \a opt.params, range-checked, and --seed.
 * \return kOk or kUsage (after fail()) */
inline int parseNumberOptions(Options& opt)
{
  if (opt.demo)
    opt.params.num_threads = default_demo_threads;
  const std::string error = pcl::phaser::setEngineOptions(opt.line.engine, opt.params);
  if (!error.empty())
    return (fail(opt.error, kUsage, "%s.", error.c_str()));
  std::string text;
  long v = opt.seed;
  if (opt.line.value("--seed", text) && !pcl::phaser::parseInteger(text, 0, INT_MAX, v))
    return (fail(opt.error, kUsage,
                 "Invalid value '%s' for --seed: expected an integer in 0..%d.",
                 text.c_str(), INT_MAX));
  opt.seed = static_cast<int>(v);
  return (kOk);
}

/** \brief kParameterRanges as a Markdown table, with the defaults of
 * PhaserParameters: what --print-parameters prints and doc/parameters.md holds. */
inline std::string parameterTable()
{
  const pcl::phaser::PhaserParameters defaults;
  std::string out =
      "| field | range | default | unit | meaning |\n|---|---|---|---|---|\n";
  char row[512];
  for (const pcl::phaser::ParameterRange& r : pcl::phaser::kParameterRanges) {
    std::snprintf(row, sizeof(row), "| `%s` | %s | %s | %s | %s |\n", r.name,
                  pcl::phaser::parameterValues(r).c_str(),
                  pcl::phaser::parameterText(r, r.value(defaults)).c_str(),
                  *r.unit ? r.unit : "-", r.meaning);
    out += row;
  }
  return (out);
}

/** \brief Parse the other valued options: --icp-dist, --size.
 * \return kOk or kUsage (after fail()) */
inline int parseValueOptions(Options& opt)
{
  std::string text;
  if (opt.line.value("--icp-dist", text)) {
    if (!pcl::phaser::parseNumber(text, opt.icp_distance) || !(opt.icp_distance > 0.0))
      return (fail(opt.error, kUsage,
                   "Invalid --icp-dist '%s': expected a distance > 0 in meters.",
                   text.c_str()));
  }
  if (opt.line.value("--size", text)) {
    const std::size_t x = text.find_first_of("xX");
    long w = 0, h = 0;
    if (x == std::string::npos ||
        !pcl::phaser::parseInteger(text.substr(0, x), 16, 8192, w) ||
        !pcl::phaser::parseInteger(text.substr(x + 1), 16, 8192, h))
      return (fail(opt.error, kUsage,
                   "Invalid --size '%s': expected WxH, each in 16..8192.",
                   text.c_str()));
    opt.width = static_cast<int>(w);
    opt.height = static_cast<int>(h);
  }
  return (kOk);
}

/** \brief Parse the path options (--gt, -o, -m, --screenshot) and check their formats;
 * the demo's overlay defaults to default_demo_overlay.
 * \return kOk, kUsage, or kOutput when a screenshot cannot be saved (after fail()) */
inline int parsePathOptions(Options& opt)
{
  if (opt.line.value("--gt", opt.gt) && opt.demo)
    return (fail(opt.error, kUsage,
                 "--gt does not apply to the demo (its truth is known)."));
  if (opt.line.value("-o", opt.output) &&
      pcl::phaser::getCloudFormat(opt.output) == pcl::phaser::CloudFormat::UNKNOWN)
    return (fail(opt.error, kUsage,
                 "Invalid -o '%s': expected a .pcd, .ply or .bin file.",
                 opt.output.c_str()));
  if (opt.line.value("-m", opt.overlay) && !hasExtension(opt.overlay, ".pcd") &&
      !hasExtension(opt.overlay, ".ply"))
    return (fail(opt.error, kUsage, "Invalid -m '%s': expected a .pcd or .ply file.",
                 opt.overlay.c_str()));
  if (opt.demo && opt.overlay.empty())
    opt.overlay = default_demo_overlay;
  if (opt.line.value("--screenshot", opt.screenshot)) {
    if (!hasExtension(opt.screenshot, ".png"))
      return (fail(opt.error, kUsage,
                   "Invalid --screenshot '%s': expected a .png file.",
                   opt.screenshot.c_str()));
    std::string why; // fail now rather than after the registration
    if (!pcl::phaser::canSaveScreenshot(why))
      return (fail(opt.error, kOutput, "Cannot save --screenshot: %s", why.c_str()));
  }
  return (kOk);
}

/** \brief Parse the whole command line into \a opt, checking in this order: the
 * files and switches, the engine options and --seed, the other values, the paths. The
 * first problem is reported with fail() and ends the parsing. \return kOk, or the exit
 * code of the first problem (kUsage or kOutput) */
inline int parseOptions(int argc, char** argv, Options& opt)
{
  int code = parseFilesAndSwitches(argc, argv, opt);
  if (code == kOk)
    code = parseNumberOptions(opt);
  if (code == kOk)
    code = parseValueOptions(opt);
  if (code == kOk)
    code = parsePathOptions(opt);
  return (code);
}

} // namespace align_tool
} // namespace phaser
} // namespace pcl
