/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_bench objects: every ordered pair of the bunny views present (bun.conf's
 * views whose PLY is in the folder) whose source has at least 30 % of its points within
 * 2 mm of the target after the truth, by each method; right: RRE < 5 deg and RTE < 5
 * mm. Times in ms and in units of one 128^3 FFT measured in the same run. The ordered
 * pairs below that overlap are run too: a method's converged flag should not claim
 * them.
 */
#include "fft_yardstick.h"
#include "methods.h"
#include "objects.h"
#include "protocol.h"
#include "report.h"
#include "subcommands.h"

#include <pcl/common/transforms.h>
#include <pcl/console/print.h>
#include <pcl/kdtree/kdtree_flann.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <tuple>
#include <vector>

namespace pcl::phaser {
namespace bench {

namespace {

namespace console = pcl::console;

const char* const kFolder = "object/stanford_bunny";
constexpr double kVoxel = 0.004;         ///< leaf (m) of PCL's methods: object scale
constexpr double kOverlapRadius = 0.002; ///< m: a source point the target saw too
constexpr double kMinOverlap = 0.3;      ///< of the source's points, for a pair
constexpr double kRightDeg = 5.0, kRightM = 0.005;

/** \brief An ordered pair of views with its truth and overlap. */
struct ObjectPair {
  std::string source, target;
  double overlap = 0.0; ///< share of the source within kOverlapRadius of the target
  Eigen::Matrix4d truth = Eigen::Matrix4d::Identity(); ///< T_target_source
};

/** \brief One method on one pair; success: right, RRE < 5 deg and RTE < 5 mm. */
struct ObjectTrial : Judged {
  const ObjectPair* pair = nullptr;
  bool counted() const { return pair->overlap >= kMinOverlap; } ///< one of the pairs
};

/** \brief Reads and checks the options (the others of StudyOptions keep their
 *  defaults: seed 1, FPCS 10 s, the voxel kVoxel); false when one is invalid (recorded
 *  in \a args). phaser_xyz by default: the views carry x y z only, so
 *  pcl::PhaserRegistration<PointXYZ> (phaser would fuse an intensity channel of
 *  zeros). */
bool parseObjectOptions(BenchArguments& args, StudyOptions& o)
{
  readStudyOptions(args, o, {"phaser_xyz", "sacia", "prerejective"}, kVoxel);
  checkStudyOptions(args, o, true);
  return args.ok();
}

/** \brief The views of bun.conf whose PLY is in \a folder, in bun.conf's order. */
std::vector<ObjectView> presentViews(const std::string& folder)
{
  std::vector<ObjectView> views;
  std::ifstream in(folder + "/bun.conf");
  ObjectView view;
  for (std::string line; std::getline(in, line);)
    if (parseConfLine(line, view) && std::filesystem::exists(folder + "/" + view.file))
      views.push_back(view);
  return views;
}

/** \brief The share of \a source's points within kOverlapRadius of \a target once
 * moved by \a truth. */
double overlapOf(const Cloud& source, const pcl::KdTreeFLANN<PointT>& target,
                 const Eigen::Matrix4d& truth)
{
  Cloud moved;
  pcl::transformPointCloud(source, moved, truth);
  pcl::Indices index(1);
  std::vector<float> sq_distance(1);
  std::size_t seen = 0;
  for (const PointT& p : moved)
    seen += target.nearestKSearch(p, 1, index, sq_distance) == 1 &&
            sq_distance[0] <= kOverlapRadius * kOverlapRadius;
  return moved.empty() ? 0.0 : static_cast<double>(seen) / moved.size();
}

/** \brief Every ordered pair of \a views with its overlap (also printed to stderr),
 * sorted by source and target. */
std::vector<ObjectPair> orderedPairs(const std::vector<ObjectView>& views,
                                     const std::map<std::string, Cloud::Ptr>& clouds)
{
  std::vector<ObjectPair> pairs;
  for (const ObjectView& target : views) {
    pcl::KdTreeFLANN<PointT> tree;
    tree.setInputCloud(clouds.at(target.file));
    for (const ObjectView& source : views) {
      if (&source == &target)
        continue;
      ObjectPair pair{source.file, target.file, 0.0, objectTruth(source, target)};
      pair.overlap = overlapOf(*clouds.at(source.file), tree, pair.truth);
      std::fprintf(stderr, "objects: %s -> %s overlap %.3f%s\n", pair.source.c_str(),
                   pair.target.c_str(), pair.overlap,
                   pair.overlap >= kMinOverlap ? "" : " (below 0.3: not a pair)");
      pairs.push_back(pair);
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const ObjectPair& a, const ObjectPair& b) {
    return std::tie(a.source, a.target) < std::tie(b.source, b.target);
  });
  return pairs;
}

/** \brief Every pair by every method, after one untimed align of the first pair by
 * each method (the first align of a process plans its transforms); a CSV row each. */
std::vector<ObjectTrial> runTrials(const StudyOptions& o,
                                   const std::vector<ObjectPair>& pairs,
                                   const std::map<std::string, Cloud::Ptr>& clouds,
                                   std::ostream* csv)
{
  // pcl_phaser at its defaults but the threads
  const MethodSettings settings =
      studySettings(o.engine, o.voxel, o.seed, o.fpcs_seconds);
  std::vector<ObjectTrial> trials;
  if (pairs.empty())
    return trials;
  for (const std::string& name : o.methods)
    findMethod(name)->run(clouds.at(pairs[0].source), clouds.at(pairs[0].target),
                          settings);
  for (const ObjectPair& pair : pairs)
    for (const std::string& name : o.methods) {
      ObjectTrial t;
      static_cast<Judged&>(t) =
          judge(name,
                findMethod(name)->run(clouds.at(pair.source), clouds.at(pair.target),
                                      settings),
                pair.truth);
      t.pair = &pair;
      t.success = t.rre < kRightDeg && t.rte < kRightM;
      std::fprintf(stderr,
                   "%s -> %s (overlap %.2f) %-12s RRE %6.2f deg RTE %7.2f mm "
                   "converged %d %6.0f ms\n",
                   pair.source.c_str(), pair.target.c_str(), pair.overlap, name.c_str(),
                   t.rre, 1e3 * t.rte, t.converged ? 1 : 0, t.ms);
      if (csv)
        *csv << name << "," << pair.source << "," << pair.target << ","
             << formatValue("%.4f", pair.overlap) << "," << formatValue("%.4f", t.rre)
             << "," << formatValue("%.6f", t.rte) << "," << t.converged << ","
             << t.success << "," << formatValue("%.1f", t.ms) << std::endl;
      trials.push_back(t);
    }
  return trials;
}

/** \brief A method's trials summed up: the Summary of the pairs, and the ordered
 * pairs below kMinOverlap. */
struct MethodSummary : Summary {
  int others = 0, others_converged = 0; ///< below kMinOverlap
};

MethodSummary summarizeMethod(const std::vector<ObjectTrial>& trials,
                              const std::string& method)
{
  MethodSummary s;
  static_cast<Summary&>(s) = summarize(select(
      trials, [&](const ObjectTrial& t) { return t.method == method && t.counted(); }));
  for (const ObjectTrial& t : trials)
    if (t.method == method && !t.counted()) {
      ++s.others;
      s.others_converged += t.converged;
    }
  return s;
}

/** \brief One row per method: counts, medians of the right trials' errors, times. */
void writeMethodTable(std::ostream& md, const std::vector<ObjectTrial>& trials,
                      const std::vector<std::string>& methods, double fft_ms)
{
  md << "| method | pairs | right (5 deg / 5 mm) | converged | valid but wrong "
        "(converged, not right) | median RRE of the right (deg) | median RTE of the "
        "right (mm) | median time (ms) | median time (FFT128) | converged below 30 % "
        "overlap |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const std::string& method : methods) {
    const MethodSummary s = summarizeMethod(trials, method);
    md << "| " << method << " | " << s.n << " | " << s.ok << " | "
       << s.converged_ok + s.converged_failed << " | " << s.converged_failed << " | "
       << formatValue("%.2f", s.median_rre) << " | "
       << formatValue("%.2f", 1e3 * s.median_rte) << " | "
       << formatValue("%.0f", s.median_ms) << " | "
       << formatValue("%.1f", s.median_ms / fft_ms) << " | " << s.others_converged
       << " / " << s.others << " |\n";
  }
}

/** \brief One row per pair: its overlap and each method's errors ("c": converged). */
void writePairTable(std::ostream& md, const std::vector<ObjectTrial>& trials,
                    const std::vector<ObjectPair>& pairs,
                    const std::vector<std::string>& methods)
{
  std::vector<std::string> columns = {"source", "target", "overlap"};
  for (const std::string& method : methods)
    columns.push_back(method + " RRE (deg) / RTE (mm)");
  md << tableHeader(columns);
  for (const ObjectPair& pair : pairs) {
    md << "| " << pair.source << " | " << pair.target << " | "
       << formatValue("%.2f", pair.overlap) << " |";
    for (const std::string& method : methods)
      for (const ObjectTrial& t : trials)
        if (t.method == method && t.pair == &pair)
          md << " " << formatValue("%.2f", t.rre) << " / "
             << formatValue("%.2f", 1e3 * t.rte) << (t.converged ? " c" : "")
             << (t.success || !t.counted() ? "" : " (wrong)") << " |";
    md << "\n";
  }
}

/** \brief The command, the setup, the yardstick and the two tables. */
void writeReport(std::ostream& md, const StudyOptions& o,
                 const std::vector<ObjectPair>& pairs,
                 const std::vector<ObjectTrial>& trials, double fft_ms)
{
  const auto counted = std::count_if(pairs.begin(), pairs.end(), [](const auto& p) {
    return p.overlap >= kMinOverlap;
  });
  md << "Objects: " << counted
     << " pairs, the ordered pairs of the Stanford bunny views "
     << "of " << kFolder
     << " whose source has >= 30 % of its points within 2 mm of the "
     << "target after the truth (bun.conf); the other " << pairs.size() - counted
     << " are run for the converged flag only. Right: RRE < 5 deg and RTE < 5 mm. "
     << o.engine.num_threads << " threads; PCL's methods at a voxel of " << kVoxel
     << " m (normals 2 v, FPFH 5 v); pcl_phaser default-constructed but the threads. "
        "Each method aligned the first pair once, untimed, before the trials.\n\n"
     << yardstickLine(fft_ms);
  writeMethodTable(md, trials, o.methods, fft_ms);
  md << "\nPer ordered pair (c: converged; wrong: not right; below 0.30: not one of "
        "the pairs):\n\n";
  writePairTable(md, trials, pairs, o.methods);
}

/** \brief Runs the study: the pairs by the methods, the report and the CSV. */
int runObjectsStudy(BenchArguments& args)
{
  StudyOptions o;
  if (!parseObjectOptions(args, o))
    return args.fail();
  console::setVerbosityLevel(console::L_ERROR);
  const std::string folder =
      std::filesystem::path(o.data + "/" + kFolder).lexically_normal().string();
  if (!std::filesystem::exists(folder + "/bun.conf")) {
    std::fprintf(stderr, "objects: %s/bun.conf not found, skipping\n", folder.c_str());
    return 0;
  }
  const std::vector<ObjectView> views = presentViews(folder);
  std::map<std::string, Cloud::Ptr> clouds;
  for (const ObjectView& view : views)
    if (!(clouds[view.file] = loadFiniteScan(folder + "/" + view.file)))
      return 1; // the loader said why
  const std::vector<ObjectPair> pairs = orderedPairs(views, clouds);
  const double fft_ms = fftYardstickMs();
  std::fprintf(stderr,
               "objects: %zu views, %zu ordered pairs x %zu methods; FFT128 %.2f ms\n",
               views.size(), pairs.size(), o.methods.size(), fft_ms);
  std::ofstream csv;
  if (!o.csv.empty()) {
    csv.open(o.csv);
    csv << "method,source,target,overlap,rre_deg,rte_m,converged,right,ms\n";
  }
  const std::vector<ObjectTrial> trials =
      runTrials(o, pairs, clouds, o.csv.empty() ? nullptr : &csv);
  std::ofstream no_file; // stdout
  writeReport(openMarkdown("", no_file, args.command()), o, pairs, trials, fft_ms);
  return 0;
}

} // namespace

const Subcommand kObjects = {
    "objects",
    "the Stanford bunny views of <data>/object/stanford_bunny (truth from "
    "bun.conf): every ordered pair whose source has >= 30 % of its points within "
    "2 mm of the target after the truth; right: RRE < 5 deg and RTE < 5 mm",
    nullptr,
    {sharedOption("--data"),
     sharedOption("--methods",
                  "as compare's; default phaser_xyz,sacia,prerejective: "
                  "pcl::PhaserRegistration<PointXYZ> (the views have no "
                  "intensity), PCL's SAC-IA and prerejective on FPFH at the "
                  "object-scale voxel of 0.004 m (normals 2 v, FPFH 5 v)"),
     sharedOption("--csv")},
    true,
    2,
    runObjectsStudy};

} // namespace bench
} // namespace pcl::phaser
