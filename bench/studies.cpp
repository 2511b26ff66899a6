/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_bench compare, nees and detection: pcl_phaser against PCL's aligners on
 * the same pairs, in one process: compare (real scans of ../shared/data under random
 * large poses with exact truth, the paper's noise / sparsity / overlap sweeps, and
 * --pairs: real pairs with reference poses), nees (getCovariance() per bandwidth),
 * detection (hasConverged() on correct and wrong registrations). Writes a markdown
 * summary (stdout or --md), a CSV (--csv) and PNG plots (--plots DIR).
 */
#include "cloud_reading.h"
#include "methods.h"
#include "protocol.h"
#include "report.h"
#include "subcommands.h"
#include "transform_file.h"

#include <pcl/common/transforms.h>
#include <pcl/console/print.h>
#include <pcl/filters/filter.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>

namespace {

using namespace pcl::phaser::bench;
namespace console = pcl::console;

/** A scan of ../shared/data used under random poses. */
struct Scan {
  std::string name, file;
  double voxel; ///< leaf for PCL's methods
};

const std::vector<Scan> kScans = {
    {"hdl32", "lidar/hdl32_fastgicp/251370668.pcd", 1.0},
    {"kitti", "lidar/kitti_raw_hdl64/0000000000.bin", 1.0},
    {"kitti_synthetic", "lidar/kitti_synthetic_gt/cloud049.ply", 1.0},
};

/** A real pair with its reference pose T_target_source (file, or inline rows). */
struct Pair {
  std::string name, source, target, truth_file;
  std::vector<double> truth_rows; ///< 12 values (3 x 4) when truth_file is empty
  double voxel;
  bool centroid;
  double rte_threshold;
};

const std::vector<Pair> kPairs = {
    {"hdl32 pair (REF)",
     "lidar/hdl32_fastgicp/251371071.pcd",
     "lidar/hdl32_fastgicp/251370668.pcd",
     "lidar/hdl32_fastgicp/relative.txt",
     {},
     1.0,
     false,
     0.6},
    {"kitti_synthetic pair (GT)",
     "lidar/kitti_synthetic_gt/cloud049.ply",
     "lidar/kitti_synthetic_gt/cloud050.ply",
     "lidar/kitti_synthetic_gt/T_cloud050_cloud049_procrustes.txt",
     {},
     1.0,
     false,
     0.6},
    {"office keypoints (GT)",
     "pcl/office1_keypoints.pcd",
     "pcl/office2_keypoints.pcd",
     "",
     {-0.6946, -0.7194, -0.0051, -3.6352, 0.7194, -0.6945, -0.0100, -2.3865, 0.0037,
      -0.0106, 0.9999, 0.7778},
     0.4,
     true,
     0.6},
    {"bunny 045 -> 000 (GT)",
     "object/stanford_bunny/bun045.ply",
     "object/stanford_bunny/bun000.ply",
     "object/stanford_bunny/T_bun000_bun045.txt",
     {},
     0.004,
     true,
     0.01},
};

/** The study's options; voxel > 0 overrides the per-scan leaf of PCL's methods. */
struct Options : StudyOptions {
  std::string study;
  std::vector<std::string> scans, conditions;
  std::vector<int> bandwidths;
  int poses = 10;
  bool icp = false, pairs = false;
  double rre_threshold = 5.0, rte_threshold = 0.6, t_max = 2.0;
  double max_tilt_pose = 180.0; ///< degrees: random poses tilted less than this
};

/** The options of the compare, nees and detection studies. */
const std::vector<BenchOption> kStudyOptions = {
    sharedOption("--data"),
    {"--scans", "A,B",
     "scans under random poses: hdl32,kitti,kitti_synthetic (default all)"},
    {"--poses", "N", "random poses per scan and condition (default 10)"},
    sharedOption("--seed"),
    sharedOption(
        "--methods",
        "phaser,phaser_xyz,phaser_plain,sacia,prerejective,fpcs,kfpcs,icp,gicp,"
        "ndt or all (all but kfpcs, which ignores its time limit, and "
        "phaser_plain: phaser without the normalized refinement; default "
        "phaser,sacia)"),
    {"--conditions", "L",
     "clean,noise:PSNR,sparsity:KEEP,overlap:KEEP or 'sweeps' for the paper's points "
     "(60/50/40 dB; keep 0.5/0.25/0.1; overlap 0.5/0.25/0.1; default clean)"},
    {"--icp", nullptr, "also report each method followed by ICP (as METHOD+icp)"},
    {"--pairs", nullptr, "also run the real pairs with reference poses"},
    {"--bandwidths", "L",
     "pcl_phaser bandwidths (default --bandwidth's; nees: e.g. 32,64,128)"},
    sharedOption("--fpcs-time"),
    {"--t-max", "M", "largest random translation in meters (default 2)"},
    {"--max-tilt-pose", "DEG",
     "random rotations: uniform yaw, tilt below DEG (default 180: uniform on SO(3))"},
    sharedOption("--voxel", "leaf (m) of PCL's methods' downsampling; radii scale with "
                            "it (default per scan: 1 m for LiDAR)"),
    sharedOption("--csv"),
    sharedOption("--md"),
    sharedOption("--plots",
                 "sweep plots (gnuplot .dat/.gp, PNG when gnuplot is installed)"),
};

/** The methods of --methods all: all but kfpcs, which takes minutes per LiDAR pair (it
 *  overruns setMaxComputationTime), and phaser_plain, a variant of phaser. */
std::vector<std::string> allMethodNames()
{
  std::vector<std::string> names;
  for (const Method& m : allMethods())
    if (m.name != "kfpcs" && m.name != "phaser_plain")
      names.push_back(m.name);
  return names;
}

/** The options of \a args into \a o, "all" methods and "sweeps" conditions expanded. */
void readOptions(BenchArguments& args, Options& o)
{
  readStudyOptions(args, o, {"phaser", "sacia"}, 0.0);
  o.scans = args.list("--scans", {"hdl32", "kitti", "kitti_synthetic"});
  o.conditions = args.list("--conditions", {"clean"});
  o.poses = static_cast<int>(args.integer("--poses", 10));
  o.t_max = args.number("--t-max", 2.0);
  o.max_tilt_pose = args.number("--max-tilt-pose", 180.0);
  o.icp = args.has("--icp");
  o.pairs = args.has("--pairs");
  for (double b : args.numbers("--bandwidths", {double(o.engine.bandwidth)}))
    if (args.check(b == std::floor(b), "--bandwidths: integers"))
      o.bandwidths.push_back(static_cast<int>(b));
  if (o.methods.size() == 1 && o.methods[0] == "all")
    o.methods = allMethodNames();
  if (o.conditions.size() == 1 && o.conditions[0] == "sweeps")
    o.conditions = {"clean",        "noise:60",      "noise:50",     "noise:40",
                    "sparsity:0.5", "sparsity:0.25", "sparsity:0.1", "overlap:0.5",
                    "overlap:0.25", "overlap:0.1"};
}

/** Reads and checks the options; false when one is invalid (recorded in \a args). */
bool parseOptions(BenchArguments& args, Options& o)
{
  readOptions(args, o);
  checkStudyOptions(args, o, false);
  for (const std::string& s : o.scans)
    args.check(std::any_of(kScans.begin(), kScans.end(),
                           [&](const Scan& x) { return x.name == s; }),
               "--scans: unknown scan " + s);
  for (const std::string& c : o.conditions) {
    Condition parsed;
    args.check(parseCondition(c, parsed), "--conditions: " + c);
  }
  for (int b : o.bandwidths)
    args.check(b >= 2 && b <= 256, "--bandwidths: " + std::to_string(b));
  args.check(!(args.has("--bandwidths") && args.has("--bandwidth")) &&
                 !(args.has("--bandwidths") && args.has("-b")),
             "--bandwidths and --bandwidth: give one");
  args.check(o.poses >= 1 && o.poses <= 100000, "--poses: 1..100000");
  args.check(o.t_max >= 0.0, "--t-max: >= 0");
  args.check(o.max_tilt_pose > 0.0 && o.max_tilt_pose <= 180.0,
             "--max-tilt-pose: in (0, 180]");
  return args.ok();
}

/** Runs the requested methods on one (source, target, truth) and records the trials;
 *  PCL's methods at the leaf \a voxel unless --voxel overrides it, pcl_phaser about
 *  the centroids when \a centroid. */
class Runner {
public:
  Runner(const Options& o, std::vector<Trial>& trials)
      : o_(o)
      , trials_(trials)
  {
  }

  void run(const Trial& base, const Cloud::Ptr& source, const Cloud::Ptr& target,
           const Eigen::Matrix4d& truth, double voxel, bool centroid,
           double rte_threshold)
  {
    MethodSettings settings =
        studySettings(o_.engine, o_.voxel > 0.0 ? o_.voxel : voxel,
                      o_.seed + static_cast<unsigned>(base.pose), o_.fpcs_seconds);
    settings.centroid = centroid;
    for (const std::string& name : o_.methods) {
      const Method& method = *findMethod(name);
      const bool is_phaser = name.rfind("phaser", 0) == 0;
      for (int bandwidth : is_phaser ? o_.bandwidths : std::vector<int>{0}) {
        settings.bandwidth = bandwidth ? bandwidth : 64;
        ++done_;
        std::fprintf(stderr, "\r[%d] %-28s %-14s pose %3d %-14s B %3d   ", done_,
                     base.set.c_str(), base.sweep.c_str(), base.pose, name.c_str(),
                     bandwidth);
        MethodResult result = method.run(source, target, settings);
        Trial trial = base;
        trial.method = name;
        trial.bandwidth = bandwidth;
        record(trial, result, truth, rte_threshold);
        if (o_.icp && method.global) {
          refineWithIcp(source, target, settings, result);
          trial.method = name + "+icp";
          result.has_covariance = false;
          record(trial, result, truth, rte_threshold);
        }
      }
    }
  }

private:
  void record(Trial trial, const MethodResult& r, const Eigen::Matrix4d& truth,
              double rte_threshold)
  {
    static_cast<Judged&>(trial) = judge(trial.method, r, truth);
    trial.success = trial.rre < o_.rre_threshold && trial.rte < rte_threshold;
    trials_.push_back(trial);
  }

  const Options& o_;
  std::vector<Trial>& trials_;
  int done_ = 0;
};

/** Source = the perturbed scan seen from T^-1; the answer is T. */
Cloud::Ptr movedSource(const Cloud& scan, const Condition& condition,
                       const Eigen::Matrix4d& T, std::mt19937& rng)
{
  Cloud perturbed = scan;
  applyCondition(condition, perturbed, rng);
  auto source = pcl::make_shared<Cloud>();
  pcl::transformPointCloud(perturbed, *source, Eigen::Matrix4d(T.inverse()));
  return source;
}

std::map<std::string, Cloud::Ptr> loadScans(const Options& o)
{
  std::map<std::string, Cloud::Ptr> scans;
  for (const Scan& s : kScans)
    if (std::find(o.scans.begin(), o.scans.end(), s.name) != o.scans.end())
      if (auto cloud = loadFiniteScan(o.data + "/" + s.file))
        scans[s.name] = cloud;
  return scans;
}

const Scan& scanInfo(const std::string& name)
{
  return *std::find_if(kScans.begin(), kScans.end(),
                       [&](const Scan& s) { return s.name == name; });
}

/** Every scan x condition x pose, each seen by every method. */
void randomPoses(const Options& o, const std::map<std::string, Cloud::Ptr>& scans,
                 const std::vector<std::string>& conditions, Runner& runner)
{
  for (const auto& [name, scan] : scans)
    for (const std::string& text : conditions) {
      Condition condition;
      parseCondition(text, condition);
      // One stream per (scan, condition): adding a method or a condition leaves the
      // poses of the others unchanged.
      std::seed_seq seq{
          o.seed, static_cast<unsigned>(std::hash<std::string>{}(name + "/" + text))};
      std::mt19937 rng(seq);
      for (int k = 0; k < o.poses; ++k) {
        const Eigen::Matrix4d T =
            randomPose(rng, o.t_max, o.max_tilt_pose * M_PI / 180.0);
        const Cloud::Ptr source = movedSource(*scan, condition, T, rng);
        Trial base;
        base.set = name;
        base.sweep = condition.sweep();
        base.value = condition.value;
        base.pose = k;
        runner.run(base, source, scan, T, scanInfo(name).voxel, false, o.rte_threshold);
      }
    }
}

void realPairs(const Options& o, Runner& runner)
{
  for (const Pair& p : kPairs) {
    const Cloud::Ptr source = loadFiniteScan(o.data + "/" + p.source);
    const Cloud::Ptr target = loadFiniteScan(o.data + "/" + p.target);
    Eigen::Matrix4d truth = Eigen::Matrix4d::Identity();
    std::string error;
    if (!p.truth_file.empty()) {
      if (!pcl::phaser::loadTransform(o.data + "/" + p.truth_file, truth, &error)) {
        console::print_error("%s\n", error.c_str());
        continue;
      }
    } else {
      for (int i = 0; i < 12; ++i)
        truth(i / 4, i % 4) = p.truth_rows[static_cast<std::size_t>(i)];
    }
    if (!source || !target)
      continue;
    Trial base;
    base.set = p.name;
    base.sweep = "pair";
    runner.run(base, source, target, truth, p.voxel, p.centroid, p.rte_threshold);
  }
}

/** Correct and wrong registrations for the failure detector: normal conditions, and
 * unrelated scenes, extreme noise and tiny overlap. */
void detection(const Options& o, const std::map<std::string, Cloud::Ptr>& scans,
               Runner& runner)
{
  randomPoses(o, scans, {"clean", "noise:60", "noise:30", "noise:25", "overlap:0.05"},
              runner);
  std::mt19937 rng(o.seed + 7919u);
  for (const auto& [source_name, source_scan] : scans)
    for (const auto& [target_name, target_scan] : scans) {
      if (source_name == target_name)
        continue;
      for (int k = 0; k < o.poses; ++k) {
        const Eigen::Matrix4d T =
            randomPose(rng, o.t_max, o.max_tilt_pose * M_PI / 180.0);
        const Cloud::Ptr source = movedSource(*source_scan, Condition{}, T, rng);
        Trial base;
        base.set = source_name + " vs " + target_name;
        base.sweep = "unrelated";
        base.pose = k;
        runner.run(base, source, target_scan, T, scanInfo(target_name).voxel, false,
                   o.rte_threshold);
      }
    }
}

/** The markdown summary of the study, the CSV and the plots \a o asks for. */
void writeReports(const Options& o, const std::vector<Trial>& trials,
                  const std::string& command)
{
  std::ofstream md_file;
  std::ostream& md = openMarkdown(o.markdown, md_file, command);
  std::vector<Trial> random_trials, pair_trials;
  for (const Trial& t : trials)
    (t.sweep == "pair" ? pair_trials : random_trials).push_back(t);
  if (o.study == "compare") {
    md << "Random poses (success: RRE < " << o.rre_threshold << " deg and RTE < "
       << o.rte_threshold << " m):\n\n";
    writeSummary(md, random_trials, false);
    if (!pair_trials.empty()) {
      md << "\nReal pairs against their reference poses:\n\n";
      writeSummary(md, pair_trials, true);
    }
  } else if (o.study == "nees") {
    writeNeesSummary(md, trials);
  } else {
    writeSummary(md, trials, false);
    md << "\n";
    writeDetectionSummary(md, trials, {5, 10, 15, 20, 25, 30, 40, 60});
  }
  if (!o.csv.empty()) {
    std::ofstream csv(o.csv);
    writeCsv(csv, trials);
  }
  if (!o.plots.empty())
    for (const std::string& png : writePlots(o.plots, random_trials))
      console::print_info("wrote %s\n", png.c_str());
}

/** Runs the study named by the subcommand (compare, nees or detection). */
int runStudy(BenchArguments& args)
{
  Options o;
  o.study = args.name();
  if (!parseOptions(args, o))
    return args.fail();
  console::setVerbosityLevel(console::L_ERROR);
  const auto scans = loadScans(o);
  if (scans.empty() && !(o.study == "compare" && o.pairs)) {
    console::print_error("No scan could be read from %s (set --data to the shared data "
                         "directory).\n",
                         o.data.c_str());
    return 1;
  }
  std::vector<Trial> trials;
  Runner runner(o, trials);
  if (o.study == "compare") {
    randomPoses(o, scans, o.conditions, runner);
    if (o.pairs)
      realPairs(o, runner);
  } else if (o.study == "nees") {
    randomPoses(o, scans, o.conditions, runner);
  } else {
    detection(o, scans, runner);
  }
  std::fprintf(stderr, "\n");
  writeReports(o, trials, args.command());
  return 0;
}

} // namespace

const pcl::phaser::bench::Subcommand pcl::phaser::bench::kCompare = {
    "compare",
    "pcl_phaser against PCL's aligners: the shared scans under random poses "
    "(sweeps of noise, sparsity, overlap) and, with --pairs, real pairs",
    nullptr,
    kStudyOptions,
    true,
    2,
    runStudy};

const pcl::phaser::bench::Subcommand pcl::phaser::bench::kNees = {
    "nees",  "getCovariance() against the errors of random poses, per bandwidth",
    nullptr, kStudyOptions,
    true,    2,
    runStudy};

const pcl::phaser::bench::Subcommand pcl::phaser::bench::kDetection = {
    "detection",
    "hasConverged() on right and wrong registrations (unrelated scenes, "
    "extreme noise, tiny overlap)",
    nullptr,
    kStudyOptions,
    true,
    2,
    runStudy};
