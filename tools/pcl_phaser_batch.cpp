// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file pcl_phaser_batch.cpp
 * \brief pcl_phaser_batch: many registrations in one process, as verified pose-graph
 * edges: pair lists or loop-closure candidates from a trajectory in, one JSON record
 * per pair and a g2o graph out; resumable, shardable (GNU parallel, Slurm arrays), and
 * `merge` to join the shards. Options and exit codes: printHelp().
 */
#include "batch_pairs.h"
#include "batch_records.h"
#include "batch_runner.h"
#include "cloud_reading.h"
#include "engine_options.h"
#include "loop_triangles.h"
#include "process_memory.h"

#include <pcl/console/print.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

using namespace pcl::console;
namespace batch = pcl::phaser::batch;

namespace {

/** \brief Jobs by default: one per hardware thread, at most 4 (each job holds an
 *  align's memory and its prepared targets). Two jobs of one engine thread align
 *  more pairs per second than one job of two (doc/benchmarks.md, loop closures). */
int defaultJobs()
{
  return std::clamp(pcl::phaser::resolveThreadCount(0), 1, 4);
}

void printHelp(const char* name)
{
  std::printf(
      "Syntax: %s --pairs LIST --out RESULTS.jsonl [options]\n"
      "        %s --scans LIST --poses POSES --radius R --min-gap K "
      "(--out RESULTS.jsonl | --print-pairs) [options]\n"
      "        %s merge OUT PARTS...\n"
      "        %s triangles RESULTS.jsonl\n"
      "  Registers every pair with PHASER, each target prepared once, and appends one "
      "JSON record\n  per pair to RESULTS.jsonl as it finishes; rerunning the same "
      "command resumes.\n"
      "    --pairs LIST      = one pair per line: SOURCE TARGET [12 numbers: row-major "
      "3x4 guess of\n"
      "                        T_target_source]; '#' comments; relative paths against "
      "LIST's folder\n"
      "    --scans LIST      = one scan path per line; with --poses (one row-major 3x4 "
      "T_world_scan per line,\n"
      "                        the last 12 numbers) every pair within --radius m and "
      "at least --min-gap scans\n"
      "                        apart, the earlier scan as target\n"
      "    --print-pairs     = print those candidates as a --pairs list and exit\n"
      "    --g2o FILE        = write the converged pairs as EDGE_SE3:QUAT (i = target, "
      "j = source) with\n"
      "                        their information; with --poses the VERTEX_SE3:QUAT "
      "lines too\n"
      "    --odometry        = with --scans/--poses: also FIX 0 and an EDGE_SE3:QUAT "
      "between consecutive\n"
      "                        scans from the poses, a complete pose graph "
      "(pcl_phaser_optimize)\n"
      "    --odometry-sigma T,R = an odometry edge's standard deviations, meters and "
      "degrees (default 0.05,0.5)\n"
      "    --shard K/N       = the K-th of N disjoint parts, K = 0..N-1 (default: "
      "SLURM_ARRAY_TASK_ID /\n"
      "                        SLURM_ARRAY_TASK_COUNT when set, else 0/1)\n"
      "    --jobs J          = pairs aligned at once, 1..64, each job taking whole "
      "target groups (default: %d)\n"
      "    --cache N         = prepared targets kept per job, 1..4096 (default: 4)\n"
      "  Engine settings, as in pcl_phaser_align (doc/parameters.md; --threads: per "
      "job, 0 splits the\n  hardware threads between the jobs; --region: every "
      "source against its target, e.g. one map):\n%s"
      "  merge OUT PARTS... joins shard outputs: .jsonl parts into OUT.jsonl (every "
      "pair exactly once),\n"
      "  .g2o parts into OUT.g2o. triangles: around every triangle of converged "
      "edges, the closure's NEES\n"
      "  under the propagated covariances (a check of them that needs no reference "
      "poses).\n"
      "  Exit codes: 0 done (failed pairs are recorded with "
      "their reason),\n"
      "  1 usage, 2 unreadable input list, 3 output not writable, 130 stopped by "
      "SIGINT/SIGTERM (resume).\n",
      name, name, name, name, defaultJobs(),
      pcl::phaser::engineOptionsHelp(pcl::phaser::PhaserParameters()).c_str());
}

int usage(const std::string& reason)
{
  print_error("%s (see -h)\n", reason.c_str());
  return batch::kUsage;
}

using Given = pcl::phaser::CommandLine;

int collect(int argc, char** argv, Given& given)
{
  static const std::set<std::string> switches = {"--print-pairs", "--odometry", "-h",
                                                 "--help"};
  static const std::set<std::string> valued = {
      "--pairs", "--scans", "--poses", "--radius", "--min-gap",       "--out",
      "--g2o",   "--shard", "--cache", "--jobs",   "--odometry-sigma"};
  std::string error =
      pcl::phaser::collectArguments(argc, argv, switches, valued, given);
  if (error.empty() && !given.files.empty())
    error = "Unknown argument '" + given.files[0] + "'";
  return error.empty() ? batch::kOk : usage(error);
}

/** \brief An integer option in [lo, hi] into \a value (left alone when absent). */
int integer(const Given& given, const std::string& name, long lo, long hi, int& value)
{
  const auto it = given.find(name);
  if (it == given.end())
    return batch::kOk;
  long v = 0;
  if (!pcl::phaser::parseInteger(it->second, lo, hi, v))
    return usage("Invalid value '" + it->second + "' for " + name +
                 ": expected an integer in [" + std::to_string(lo) + ", " +
                 std::to_string(hi) + "]");
  value = static_cast<int>(v);
  return batch::kOk;
}

int engineSettings(const Given& given, pcl::phaser::PhaserParameters& p, int& cache,
                   int& jobs)
{
  for (const int rc : {integer(given, "--cache", 1, 4096, cache),
                       integer(given, "--jobs", 1, 64, jobs)})
    if (rc != batch::kOk)
      return rc;
  const std::string error = pcl::phaser::setEngineOptions(given.engine, p);
  return error.empty() ? batch::kOk : usage(error);
}

/** \brief --shard, else the Slurm array task, else 0/1. */
int shardSettings(const Given& given, int& k, int& n)
{
  std::string text = given.count("--shard") ? given.at("--shard") : "";
  const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
  if (text.empty() && id && count) {
    const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
    text = std::to_string(std::atol(id) - (min ? std::atol(min) : 0)) + "/" + count;
  }
  if (text.empty())
    text = "0/1";
  const auto shard = batch::parseShard(text);
  if (!shard)
    return usage("Invalid shard '" + text + "': expected K/N with 0 <= K < N");
  std::tie(k, n) = *shard;
  return batch::kOk;
}

/** \brief Loop-closure candidates from --scans, --poses, --radius, --min-gap. */
int candidates(const Given& given, batch::PairList& list)
{
  for (const char* name : {"--poses", "--radius", "--min-gap"})
    if (!given.count(name))
      return usage(std::string("--scans needs ") + name);
  const std::string& radius_text = given.at("--radius");
  double radius = 0.0;
  if (!pcl::phaser::parseNumber(radius_text, radius) || !(radius > 0.0))
    return usage("Invalid --radius '" + radius_text + "': expected meters > 0");
  int gap = 1;
  if (const int rc = integer(given, "--min-gap", 1, 1000000, gap); rc != batch::kOk)
    return rc;
  std::vector<std::string> names, paths;
  std::vector<Eigen::Matrix4d> poses;
  const std::string error = batch::readTrajectory(
      given.at("--scans"), given.at("--poses"), names, paths, poses);
  if (!error.empty())
    return print_error("%s\n", error.c_str()), batch::kInput;
  list = batch::makeCandidates(names, paths, poses, radius, gap);
  return batch::kOk;
}

/** \brief --odometry and --odometry-sigma T_M,R_DEG into \a odometry. */
int odometrySettings(const Given& given, std::optional<batch::OdometrySigma>& odometry)
{
  if (given.count("--odometry-sigma") && !given.count("--odometry"))
    return usage("--odometry-sigma needs --odometry");
  if (!given.count("--odometry"))
    return batch::kOk;
  if (!given.count("--scans") || !given.count("--g2o"))
    return usage("--odometry needs --scans, --poses and --g2o");
  batch::OdometrySigma sigma;
  if (given.count("--odometry-sigma")) {
    const std::string& text = given.at("--odometry-sigma");
    // 1e-6 m and deg at least: the information (1 / sigma^2) must stay finite.
    if (!pcl::phaser::parseNumberPair(text, sigma.translation, sigma.rotation_deg) ||
        !(sigma.translation >= 1e-6) || !(sigma.rotation_deg >= 1e-6))
      return usage("Invalid --odometry-sigma '" + text +
                   "': expected T_M,R_DEG, two finite numbers >= 1e-6");
  }
  odometry = sigma;
  return batch::kOk;
}

int merge(int argc, char** argv)
{
  if (argc < 4)
    return usage("merge needs OUT and at least one part");
  const std::vector<std::string> parts(argv + 3, argv + argc);
  const std::string error = batch::mergeParts(argv[2], parts);
  if (error.empty())
    return batch::kOk;
  print_error("merge: %s\n", error.c_str());
  return error.rfind("cannot write", 0) == 0 ? batch::kOutput : batch::kInput;
}

int run(const Given& given)
{
  batch::RunSettings settings;
  settings.jobs = defaultJobs();
  for (const int rc :
       {engineSettings(given, settings.params, settings.cache, settings.jobs),
        shardSettings(given, settings.shard, settings.shards),
        odometrySettings(given, settings.odometry)})
    if (rc != batch::kOk)
      return rc;
  if (given.count("--pairs") == given.count("--scans"))
    return usage("Give either --pairs or --scans");
  batch::PairList list;
  if (given.count("--scans")) {
    if (const int rc = candidates(given, list); rc != batch::kOk)
      return rc;
  } else if (const std::string error = batch::readPairList(given.at("--pairs"), list);
             !error.empty())
    return print_error("%s\n", error.c_str()), batch::kInput;
  if (given.count("--print-pairs"))
    return std::cout << batch::formatPairList(list) << std::flush, batch::kOk;
  if (!given.count("--out"))
    return usage("--out RESULTS.jsonl is required");
  settings.out = given.at("--out");
  settings.g2o = given.count("--g2o") ? given.at("--g2o") : "";
  return batch::runBatch(list, settings);
}

} // namespace

/** \brief `triangles RESULTS.jsonl`: the reference-free covariance check. */
int triangles(int argc, char** argv)
{
  if (argc != 3)
    return usage("triangles needs one RESULTS.jsonl");
  std::vector<batch::Record> records;
  if (const std::string error = batch::readRecords(argv[2], records, false);
      !error.empty())
    return print_error("triangles: %s\n", error.c_str()), batch::kInput;
  std::printf("%s\n", batch::closureSummary(batch::loopClosures(records)).c_str());
  return batch::kOk;
}

int main(int argc, char** argv)
{
  if (argc >= 2 && std::string(argv[1]) == "merge")
    return merge(argc, argv);
  if (argc >= 2 && std::string(argv[1]) == "triangles")
    return triangles(argc, argv);
  pcl::phaser::preferHugePages(); // before the reader process: it inherits the heap
  // While this process is small: it reads every cloud from here on
  // (io/cloud_reading.h).
  pcl::phaser::startCloudReader();
  Given given;
  if (const int rc = collect(argc, argv, given); rc != batch::kOk)
    return rc;
  if (argc == 1 || given.count("-h") || given.count("--help"))
    return printHelp(argv[0]), argc == 1 ? batch::kUsage : batch::kOk;
  return run(given);
}
