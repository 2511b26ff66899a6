/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_optimize: optimize the pose graph pcl_phaser_batch --g2o --odometry wrote
 * (Ceres), write the optimized poses in the --poses format and a top-view PNG of the
 * trajectory (gnuplot) before (red) and after (blue), loop edges (gray), the reference
 * (green); --drift makes a graph's odometry drift first (the loop-closure demo).
 */
#include "batch_pairs.h"
#include "batch_records.h"
#include "engine_options.h"
#include "pose_graph.h"
#include "trajectory_plot.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

namespace {

namespace graph = pcl::phaser::graph;

constexpr int kUsage = 1, kInput = 2, kOutput = 3;

int usage(const char* name)
{
  std::fprintf(
      stderr,
      "Syntax: %s GRAPH.g2o OUT_POSES.txt [--png OUT.png] [--loss "
      "none|huber|cauchy]\n"
      "          [--reference POSES.txt] [--drift DEG,FRACTION]\n"
      "  Optimizes the graph (FIX vertices held, else the first), writes one "
      "row-major 3x4\n"
      "  T_world_vertex per vertex in id order; --loss (default huber, scale 3.55 "
      "on the whitened\n"
      "  error) applies to every edge; --reference prints the trajectory "
      "error (RMS after the\n"
      "  best rigid alignment) before and after. --png draws the top view with "
      "gnuplot (Debian\n"
      "  gnuplot-nox): before (red), optimized (blue), reference (green), loop "
      "edges (gray).\n"
      "  --drift DEG,FRACTION makes the odometry drift before optimizing: each "
      "edge to the next\n"
      "  vertex turned DEG degrees (yaw) and its translation scaled by 1 + "
      "FRACTION, the initial\n"
      "  poses chained from them (e.g. --drift 1.5,0.05 on a graph made from "
      "accurate poses).\n"
      "  Exit codes: 0 done, 1 usage, 2 unreadable or malformed input, 3 output "
      "not written.\n",
      name);
  return kUsage;
}

struct Options {
  std::string graph, out, png, reference;
  graph::Loss loss = graph::Loss::Huber;
  bool drift = false;
  double drift_deg = 0.0, drift_fraction = 0.0;
};

/** --drift DEG,FRACTION: two finite numbers, FRACTION > -1. */
bool parseDrift(const std::string& text, Options& o)
{
  o.drift = true;
  return pcl::phaser::parseNumberPair(text, o.drift_deg, o.drift_fraction) &&
         o.drift_fraction > -1.0;
}

/** \a argv into \a o; empty, or the problem. */
std::string parse(int argc, char** argv, Options& o)
{
  static const std::map<std::string, graph::Loss> losses = {
      {"none", graph::Loss::None},
      {"huber", graph::Loss::Huber},
      {"cauchy", graph::Loss::Cauchy}};
  pcl::phaser::CommandLine line;
  std::string error = pcl::phaser::collectArguments(
      argc, argv, {}, {"--png", "--loss", "--reference", "--drift"}, line, false);
  std::string text;
  if (error.empty() && line.files.size() != 2)
    error = "expected GRAPH.g2o and OUT_POSES.txt";
  else if (error.empty() && line.value("--drift", text) && !parseDrift(text, o))
    error = "Invalid --drift '" + text + "': expected DEG,FRACTION, FRACTION > -1";
  else if (error.empty() && line.value("--loss", text)) {
    const auto it = losses.find(text);
    if (it == losses.end())
      error = "Invalid --loss '" + text + "': expected none, huber or cauchy";
    else
      o.loss = it->second;
  }
  if (!error.empty())
    return error;
  line.value("--png", o.png);
  line.value("--reference", o.reference);
  o.graph = line.files[0];
  o.out = line.files[1];
  return {};
}

std::vector<Eigen::Vector2d> path(const std::map<int, Eigen::Isometry3d>& poses)
{
  std::vector<Eigen::Vector2d> out;
  for (const auto& [id, T] : poses)
    out.push_back(T.translation().head<2>());
  return out;
}

std::string format(const char* pattern, double a, double b = 0.0)
{
  char text[200];
  std::snprintf(text, sizeof(text), pattern, a, b);
  return text;
}

/** The top view: loop edges (on the optimized poses), reference, before, after; the
 *  errors against the reference, \a before_error and \a after_error, in the legend. */
std::string draw(const Options& o, const graph::PoseGraph& before,
                 const graph::PoseGraph& after,
                 const std::map<int, Eigen::Isometry3d>& reference, double before_error,
                 double after_error)
{
  graph::Series loops{"", {}, "#a0a0a0", 1.0, false};
  for (const graph::Edge& e : after.edges)
    if (!e.odometry) {
      loops.points.push_back(after.vertices.at(e.from).translation().head<2>());
      loops.points.push_back(after.vertices.at(e.to).translation().head<2>());
    }
  loops.title = "loop edges (" + std::to_string(loops.points.size() / 2) + ")";
  const bool known = !reference.empty();
  std::string start = "before optimization: ";
  start += o.drift ? format("odometry drifted %.3g deg and %.3g %% a step", o.drift_deg,
                            100.0 * o.drift_fraction)
                   : std::string("the graph's initial poses");
  start += known ? format(", RMS error %.3f m", before_error) : "";
  const std::vector<graph::Series> lines = {
      loops,
      {"reference (--reference)", path(reference), "#20a040", 2.0, true},
      {start, path(before.vertices), "#d02020", 2.0, true},
      {known ? format("optimized, RMS error %.3f m", after_error) : "optimized",
       path(after.vertices), "#2040d0", 2.0, true}};
  const std::string title =
      std::to_string(after.vertices.size()) +
      " poses and their loop edges, top view\n" +
      (known ? format("trajectory RMS error against the reference (after the best "
                      "rigid alignment): %.3f m before, %.3f m after",
                      before_error, after_error)
             : "no --reference given: no trajectory error");
  return graph::writeTopView(o.png, title, lines);
}

} // namespace

int main(int argc, char** argv)
{
  Options o;
  if (const std::string error = parse(argc, argv, o); !error.empty())
    return std::fprintf(stderr, "Error: %s\n", error.c_str()), usage(argv[0]);
  graph::PoseGraph g;
  if (const std::string error = graph::readG2o(o.graph, g); !error.empty())
    return std::fprintf(stderr, "Error: %s\n", error.c_str()), kInput;
  std::map<int, Eigen::Isometry3d> reference;
  if (!o.reference.empty()) {
    std::vector<Eigen::Matrix4d> poses;
    if (const std::string error = pcl::phaser::batch::readPoses(o.reference, poses);
        !error.empty())
      return std::fprintf(stderr, "Error: %s\n", error.c_str()), kInput;
    for (std::size_t i = 0; i < poses.size(); ++i)
      reference[static_cast<int>(i)] = Eigen::Isometry3d(poses[i]);
  }
  if (o.drift)
    if (const std::string error =
            graph::driftOdometry(g, o.drift_deg, o.drift_fraction);
        !error.empty())
      return std::fprintf(stderr, "Error: --drift: %s\n", error.c_str()), kInput;
  const graph::PoseGraph before = g;
  std::string summary;
  if (const std::string error = graph::optimize(g, o.loss, &summary); !error.empty())
    return std::fprintf(stderr, "Error: %s\n", error.c_str()), kInput;
  std::printf("%zu vertices, %zu edges: %s\n", g.vertices.size(), g.edges.size(),
              summary.c_str());
  const double before_error = graph::trajectoryError(before.vertices, reference),
               after_error = graph::trajectoryError(g.vertices, reference);
  if (!reference.empty())
    std::printf("trajectory error against the reference: %.3f m before, %.3f m after\n",
                before_error, after_error);
  if (const std::string error =
          pcl::phaser::batch::writeFileAtomically(o.out, graph::posesText(g));
      !error.empty())
    return std::fprintf(stderr, "Error: %s\n", error.c_str()), kOutput;
  if (!o.png.empty())
    if (const std::string error =
            draw(o, before, g, reference, before_error, after_error);
        !error.empty())
      return std::fprintf(stderr, "Error: --png: %s\n", error.c_str()), kOutput;
  return 0;
}
