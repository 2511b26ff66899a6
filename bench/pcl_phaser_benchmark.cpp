/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_benchmark: pcl_phaser against PCL's aligners on the same pairs, in one
 * process. Studies: compare (real scans of ../shared/data under random large poses with
 * exact truth, the paper's noise / sparsity / overlap sweeps, and -pairs: real pairs
 * with reference poses), nees (getCovariance() per bandwidth), detection
 * (hasConverged() on correct and wrong registrations), revisits (revisits.h) and
 * objects (objects.h). Writes a markdown summary (stdout or -md), a CSV (-csv) and PNG
 * plots (-plots DIR).
 */
#include "cloud_reading.h"
#include "methods.h"
#include "objects.h"
#include "protocol.h"
#include "report.h"
#include "revisits.h"
#include "transform_file.h"

#include <pcl/common/transforms.h>
#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/filters/filter.h>

#include <Eigen/Geometry>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

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

struct Options {
  std::string study = "compare", data = PCL_PHASER_DEFAULT_DATA_DIR;
  std::vector<std::string> scans = {"hdl32", "kitti", "kitti_synthetic"};
  std::vector<std::string> methods = {"phaser", "sacia"};
  std::vector<std::string> conditions = {"clean"};
  std::vector<int> bandwidths = {64};
  int poses = 10, threads = 2, fpcs_seconds = 10;
  int orientation_candidates = -1; ///< pcl_phaser's; < 0: its default
  unsigned seed = 1;
  bool icp = false, pairs = false;
  double rre_threshold = 5.0, rte_threshold = 0.6, t_max = 2.0;
  double max_tilt_pose = 180.0; ///< degrees: random poses tilted less than this
  double max_tilt = 0.0;        ///< pcl_phaser's PhaserParameters::max_tilt_deg
  double voxel = 0.0;           ///< > 0: overrides the per-scan leaf of PCL's methods
  std::string center;           ///< pcl_phaser's projection center; empty: its default
  std::string csv, markdown, plots;
};

void printHelp(const char* program)
{
  console::print_info(
      "Usage: %s [options]\n"
      "  -study S       compare | nees | detection | revisits | objects (default\n"
      "                 compare; revisits and objects have their own options:\n"
      "                 -study revisits -h, -study objects -h)\n"
      "  -data DIR      the shared data directory (default %s)\n"
      "  -scans A,B     scans under random poses: hdl32,kitti,kitti_synthetic\n"
      "  -poses N       random poses per scan and condition (default 10)\n"
      "  -seed S        seed of poses, perturbations and PCL's RANSAC (default 1)\n"
      "  -methods A,B   phaser,phaser_xyz,phaser_plain,sacia,prerejective,fpcs,kfpcs,\n"
      "                 icp,gicp,ndt or all (all but kfpcs, which ignores its time\n"
      "                 limit, and phaser_plain: phaser without the normalized\n"
      "                 refinement; default phaser,sacia)\n"
      "  -conditions L  clean,noise:PSNR,sparsity:KEEP,overlap:KEEP or 'sweeps' for "
      "the\n"
      "                 paper's points (60/50/40 dB; keep 0.5/0.25/0.1; overlap "
      "0.5/0.25/0.1)\n"
      "  -icp           also report each method followed by ICP (as METHOD+icp)\n"
      "  -pairs         also run the real pairs with reference poses\n"
      "  -bandwidths L  pcl_phaser bandwidths (default 64; nees: e.g. 32,64,128)\n"
      "  -threads N     threads for every method (default 2)\n"
      "  -fpcs_time S   time limit of FPCS/KFPCS in seconds (default 10)\n"
      "  -orientation_candidates N  pcl_phaser's orientation hypotheses, 0..20\n"
      "                 (default: the library's, 10)\n"
      "  -t_max M       largest random translation in meters (default 2)\n"
      "  -max_tilt_pose D  random rotations: uniform yaw, tilt below D deg (default\n"
      "                 180: uniform on SO(3))\n"
      "  -max_tilt D    pcl_phaser's gravity prior, max_tilt_deg (default 0: off)\n"
      "  -center C      pcl_phaser's projection center: sensor, centroid or auto\n"
      "                 (default: the library's)\n"
      "  -voxel V       leaf (m) of PCL's methods' downsampling; radii scale with it\n"
      "                 (default per scan: 1 m for LiDAR)\n"
      "  -csv FILE      every trial as CSV\n"
      "  -md FILE       the markdown summary (default: stdout)\n"
      "  -plots DIR     sweep plots (gnuplot .dat/.gp, PNG when gnuplot is "
      "installed)\n",
      program, PCL_PHASER_DEFAULT_DATA_DIR);
}

/** The options of \a argv into \a o, "all" methods and "sweeps" conditions expanded. */
void readOptions(int argc, char** argv, Options& o)
{
  std::string scans, methods, conditions, bandwidths;
  console::parse_argument(argc, argv, "-study", o.study);
  console::parse_argument(argc, argv, "-data", o.data);
  if (console::parse_argument(argc, argv, "-scans", scans) >= 0)
    o.scans = splitList(scans);
  if (console::parse_argument(argc, argv, "-methods", methods) >= 0)
    o.methods = splitList(methods);
  if (console::parse_argument(argc, argv, "-conditions", conditions) >= 0)
    o.conditions = splitList(conditions);
  if (console::parse_argument(argc, argv, "-bandwidths", bandwidths) >= 0) {
    o.bandwidths.clear();
    for (const std::string& b : splitList(bandwidths))
      o.bandwidths.push_back(std::atoi(b.c_str()));
  }
  console::parse_argument(argc, argv, "-poses", o.poses);
  console::parse_argument(argc, argv, "-seed", o.seed);
  console::parse_argument(argc, argv, "-threads", o.threads);
  console::parse_argument(argc, argv, "-fpcs_time", o.fpcs_seconds);
  console::parse_argument(argc, argv, "-orientation_candidates",
                          o.orientation_candidates);
  console::parse_argument(argc, argv, "-t_max", o.t_max);
  console::parse_argument(argc, argv, "-max_tilt_pose", o.max_tilt_pose);
  console::parse_argument(argc, argv, "-max_tilt", o.max_tilt);
  console::parse_argument(argc, argv, "-voxel", o.voxel);
  console::parse_argument(argc, argv, "-center", o.center);
  console::parse_argument(argc, argv, "-csv", o.csv);
  console::parse_argument(argc, argv, "-md", o.markdown);
  console::parse_argument(argc, argv, "-plots", o.plots);
  o.icp = console::find_switch(argc, argv, "-icp");
  o.pairs = console::find_switch(argc, argv, "-pairs");
  if (o.methods.size() == 1 && o.methods[0] == "all") {
    o.methods.clear();
    for (const Method& m : allMethods())
      // kfpcs takes minutes per LiDAR pair (it overruns setMaxComputationTime);
      // phaser_plain is a variant of phaser, not a peer.
      if (m.name != "kfpcs" && m.name != "phaser_plain")
        o.methods.push_back(m.name);
  }
  if (o.conditions.size() == 1 && o.conditions[0] == "sweeps")
    o.conditions = {"clean",        "noise:60",      "noise:50",     "noise:40",
                    "sparsity:0.5", "sparsity:0.25", "sparsity:0.1", "overlap:0.5",
                    "overlap:0.25", "overlap:0.1"};
}

bool parseOptions(int argc, char** argv, Options& o)
{
  readOptions(argc, argv, o);
  bool ok = true;
  auto fail = [&](const std::string& what) {
    console::print_error("Invalid option: %s\n", what.c_str());
    ok = false;
  };
  if (o.study != "compare" && o.study != "nees" && o.study != "detection")
    fail("-study " + o.study);
  for (const std::string& m : o.methods)
    if (std::none_of(allMethods().begin(), allMethods().end(),
                     [&](const Method& x) { return x.name == m; }))
      fail("-methods: unknown method " + m);
  for (const std::string& s : o.scans)
    if (std::none_of(kScans.begin(), kScans.end(),
                     [&](const Scan& x) { return x.name == s; }))
      fail("-scans: unknown scan " + s);
  for (const std::string& c : o.conditions) {
    Condition parsed;
    if (!parseCondition(c, parsed))
      fail("-conditions: " + c);
  }
  for (int b : o.bandwidths)
    if (b < 2 || b > 256)
      fail("-bandwidths: " + std::to_string(b));
  if (o.poses < 1 || o.poses > 100000)
    fail("-poses");
  if (o.threads < 1 || o.threads > 256)
    fail("-threads");
  if (o.fpcs_seconds < 1)
    fail("-fpcs_time");
  if (o.orientation_candidates > 20)
    fail("-orientation_candidates");
  if (!(o.t_max >= 0.0))
    fail("-t_max");
  if (!(o.max_tilt_pose > 0.0 && o.max_tilt_pose <= 180.0))
    fail("-max_tilt_pose");
  if (!(o.max_tilt >= 0.0 && o.max_tilt <= 180.0))
    fail("-max_tilt");
  if (!o.center.empty() && o.center != "sensor" && o.center != "centroid" &&
      o.center != "auto")
    fail("-center " + o.center);
  return ok;
}

/** Runs the requested methods on one (source, target, truth) and records the trials. */
class Runner {
public:
  Runner(const Options& o, std::vector<Trial>& trials)
      : o_(o)
      , trials_(trials)
  {
  }

  void run(const Trial& base, const Cloud::Ptr& source, const Cloud::Ptr& target,
           const Eigen::Matrix4d& truth, MethodSettings settings, double rte_threshold)
  {
    settings.threads = o_.threads;
    if (o_.voxel > 0.0)
      settings.voxel = o_.voxel;
    settings.seed = o_.seed + static_cast<unsigned>(base.pose);
    settings.fpcs_seconds = o_.fpcs_seconds;
    settings.orientation_candidates = o_.orientation_candidates;
    settings.max_tilt_deg = o_.max_tilt;
    settings.center = o_.center;
    for (const std::string& name : o_.methods) {
      const Method& method =
          *std::find_if(allMethods().begin(), allMethods().end(),
                        [&](const Method& m) { return m.name == name; });
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
    trial.rre_deg = rreDeg(r.transformation, truth);
    trial.rte_m = rteM(r.transformation, truth);
    trial.ms = r.ms;
    trial.converged = r.converged;
    trial.success = trial.rre_deg < o_.rre_threshold && trial.rte_m < rte_threshold;
    trial.score = r.score;
    trial.phaser = r.phaser;
    if (r.has_covariance) {
      const NeesFigures f = neesOf(r, truth);
      trial.nees = f.nees;
      trial.nees_rot = f.nees_rot;
      trial.nees_trans = f.nees_trans;
      trial.sigma_rot_deg = f.sigma_rot_deg;
      trial.sigma_trans_m = f.sigma_trans_m;
    }
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
        MethodSettings settings;
        settings.voxel = scanInfo(name).voxel;
        runner.run(base, source, scan, T, settings, o.rte_threshold);
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
    MethodSettings settings;
    settings.voxel = p.voxel;
    settings.centroid = p.centroid;
    runner.run(base, source, target, truth, settings, p.rte_threshold);
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
        MethodSettings settings;
        settings.voxel = scanInfo(target_name).voxel;
        runner.run(base, source, target_scan, T, settings, o.rte_threshold);
      }
    }
}

} // namespace

/** The markdown summary of the study, the CSV and the plots \a o asks for. */
void writeReports(const Options& o, const std::vector<Trial>& trials, int argc,
                  char** argv)
{
  std::ofstream md_file;
  if (!o.markdown.empty())
    md_file.open(o.markdown);
  std::ostream& md = o.markdown.empty() ? std::cout : md_file;
  std::ostringstream command;
  for (int i = 0; i < argc; ++i)
    command << (i ? " " : "") << argv[i];
  md << "Command: `" << command.str() << "`\n\n";
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

int main(int argc, char** argv)
{
  if (isRevisitsStudy(argc, argv))
    return runRevisitsStudy(argc, argv);
  if (isObjectsStudy(argc, argv))
    return runObjectsStudy(argc, argv);
  if (console::find_switch(argc, argv, "-h") ||
      console::find_switch(argc, argv, "--help")) {
    printHelp(argv[0]);
    return 0;
  }
  Options o;
  if (!parseOptions(argc, argv, o)) {
    printHelp(argv[0]);
    return 2;
  }
  console::setVerbosityLevel(console::L_ERROR);
  const auto scans = loadScans(o);
  if (scans.empty() && !(o.study == "compare" && o.pairs)) {
    console::print_error("No scan could be read from %s (set -data to the shared data "
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
  writeReports(o, trials, argc, argv);
  return 0;
}
