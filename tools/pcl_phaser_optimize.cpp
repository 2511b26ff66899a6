/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_optimize: optimize the pose graph pcl_phaser_batch --g2o --odometry wrote
 * (Ceres), write the optimized poses in the --poses format and a top-view PNG of the
 * trajectory before (red) and after (blue), loop edges (gray), the reference (green).
 */
#include "batch_pairs.h"
#include "batch_records.h"
#include "pose_graph.h"
#include "trajectory_plot.h"

#include <cstdio>
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
      "          [--reference POSES.txt]\n"
      "  Optimizes the graph (FIX vertices held, else the first), writes one "
      "row-major 3x4\n"
      "  T_world_vertex per vertex in id order; --loss (default huber, scale 3.55 "
      "on the whitened\n"
      "  error) applies to every edge; --reference prints the trajectory "
      "error (RMS after the\n"
      "  best rigid alignment) before and after, and draws it. Exit codes: 0 "
      "done, 1 usage,\n"
      "  2 unreadable or malformed input, 3 output not written.\n",
      name);
  return kUsage;
}

struct Options {
  std::string graph, out, png, reference;
  graph::Loss loss = graph::Loss::Huber;
};

bool parse(int argc, char** argv, Options& o)
{
  const std::map<std::string, graph::Loss> losses = {{"none", graph::Loss::None},
                                                     {"huber", graph::Loss::Huber},
                                                     {"cauchy", graph::Loss::Cauchy}};
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool valued = a == "--png" || a == "--loss" || a == "--reference";
    if (valued && i + 1 >= argc)
      return false;
    if (a == "--png")
      o.png = argv[++i];
    else if (a == "--reference")
      o.reference = argv[++i];
    else if (a == "--loss") {
      const auto it = losses.find(argv[++i]);
      if (it == losses.end())
        return false;
      o.loss = it->second;
    } else if (a.rfind("-", 0) == 0)
      return false;
    else
      positional.push_back(a);
  }
  if (positional.size() != 2)
    return false;
  o.graph = positional[0];
  o.out = positional[1];
  return true;
}

std::vector<Eigen::Vector2d> path(const std::map<int, Eigen::Isometry3d>& poses)
{
  std::vector<Eigen::Vector2d> out;
  for (const auto& [id, T] : poses)
    out.push_back(T.translation().head<2>());
  return out;
}

/** The top view: reference, loop edges on the optimized poses, before, after. */
std::string draw(const Options& o, const graph::PoseGraph& before,
                 const graph::PoseGraph& after,
                 const std::map<int, Eigen::Isometry3d>& reference)
{
  std::vector<graph::Polyline> lines;
  lines.push_back({path(reference), {40, 170, 60}, true});
  graph::Polyline loops{{}, {170, 170, 170}, false};
  for (const graph::Edge& e : after.edges)
    if (!e.odometry) {
      loops.points.push_back(after.vertices.at(e.from).translation().head<2>());
      loops.points.push_back(after.vertices.at(e.to).translation().head<2>());
    }
  lines.push_back(loops);
  lines.push_back({path(before.vertices), {220, 40, 40}, true});
  lines.push_back({path(after.vertices), {40, 70, 220}, true});
  return graph::writeTopView(o.png, lines);
}

} // namespace

int main(int argc, char** argv)
{
  Options o;
  if (!parse(argc, argv, o))
    return usage(argv[0]);
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
  const graph::PoseGraph before = g;
  std::string summary;
  if (const std::string error = graph::optimize(g, o.loss, &summary); !error.empty())
    return std::fprintf(stderr, "Error: %s\n", error.c_str()), kInput;
  std::printf("%zu vertices, %zu edges: %s\n", g.vertices.size(), g.edges.size(),
              summary.c_str());
  if (!reference.empty())
    std::printf("trajectory error against the reference: %.3f m before, %.3f m after\n",
                graph::trajectoryError(before.vertices, reference),
                graph::trajectoryError(g.vertices, reference));
  if (const std::string error =
          pcl::phaser::batch::writeFileAtomically(o.out, graph::posesText(g));
      !error.empty())
    return std::fprintf(stderr, "Error: %s\n", error.c_str()), kOutput;
  if (!o.png.empty())
    if (const std::string error = draw(o, before, g, reference); !error.empty())
      return std::fprintf(stderr, "Error: %s\n", error.c_str()), kOutput;
  return 0;
}
