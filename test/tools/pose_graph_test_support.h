/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * What the pose-graph tests (test_pose_graph.cpp) and the loop-closure tests on the
 * shared scans (test_loop_closures.cpp) share: drifted trajectories, g2o edges, a
 * square walk, the optimizer's outputs read back.
 */
#pragma once

#include "../registration/test_data.h"
#include "batch_pairs.h"
#include "batch_records.h"
#include "loop_triangles.h"
#include "pose_graph.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <utility>
#include <vector>

namespace pose_graph_test {

namespace batch = pcl::phaser::batch;
namespace graph = pcl::phaser::graph;

inline std::string freshFolder()
{
  char name[] = "/tmp/pcl_phaser_pose_graph_XXXXXX";
  return ::mkdtemp(name) ? name : "/tmp";
}

/** A yaw of \a deg degrees. */
inline Eigen::Matrix4d yaw(double deg)
{
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
  return T;
}

/** \a truth's odometry with a heading bias of \a bias_deg per step before each move and
 *  its translations scaled by \a scale, from truth[0]. */
inline std::vector<Eigen::Matrix4d> drifted(const std::vector<Eigen::Matrix4d>& truth,
                                            double bias_deg, double scale)
{
  std::vector<Eigen::Matrix4d> out = {truth[0]};
  for (std::size_t i = 0; i + 1 < truth.size(); ++i) {
    Eigen::Matrix4d step = truth[i].inverse() * truth[i + 1];
    step.topRightCorner<3, 1>() *= scale;
    out.push_back(out.back() * yaw(bias_deg) * step);
  }
  return out;
}

inline std::map<int, Eigen::Isometry3d> byId(const std::vector<Eigen::Matrix4d>& poses)
{
  std::map<int, Eigen::Isometry3d> out;
  for (std::size_t i = 0; i < poses.size(); ++i)
    out[static_cast<int>(i)] = Eigen::Isometry3d(poses[i]);
  return out;
}

/** An EDGE_SE3:QUAT i j measuring T_i^-1 T_j of \a truth, information 1e4 / 1e6. */
inline std::string loopEdge(int i, int j, const std::vector<Eigen::Matrix4d>& truth)
{
  const Eigen::Matrix4d Z =
      truth[static_cast<std::size_t>(i)].inverse() * truth[static_cast<std::size_t>(j)];
  const Eigen::Quaterniond q(Eigen::Matrix3d(Z.topLeftCorner<3, 3>()));
  std::ostringstream line;
  line.precision(17);
  line << "EDGE_SE3:QUAT " << i << " " << j << " " << Z(0, 3) << " " << Z(1, 3) << " "
       << Z(2, 3) << " " << q.x() << " " << q.y() << " " << q.z() << " " << q.w();
  for (int r = 0; r < 6; ++r)
    for (int c = r; c < 6; ++c)
      line << " " << (r != c ? 0.0 : r < 3 ? 1e4 : 1e6);
  return line.str();
}

/** The exit code of a std::system status, -1 when the program did not exit. */
inline int exitCode(int status)
{
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/** Whether an executable \a program is on PATH. */
inline bool onPath(const std::string& program)
{
  const char* env = std::getenv("PATH");
  std::istringstream dirs(env ? env : "");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty() && ::access((dir + "/" + program).c_str(), X_OK) == 0)
      return true;
  return false;
}

#define REQUIRE_GNUPLOT()                                                              \
  do {                                                                                 \
    if (!onPath("gnuplot"))                                                            \
      GTEST_SKIP() << "gnuplot not on PATH: apt-get install gnuplot-nox";              \
  } while (false)

/** Width and height from the IHDR of the PNG at \a path, {0, 0} when it is not one. */
inline std::pair<long, long> pngSize(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  unsigned char b[24] = {};
  if (!in.read(reinterpret_cast<char*>(b), sizeof(b)) ||
      std::string(reinterpret_cast<char*>(b), 16) !=
          std::string("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16))
    return {0, 0};
  const auto u32 = [&](int at) {
    return (long{b[at]} << 24) | (long{b[at + 1]} << 16) | (long{b[at + 2]} << 8) |
           long{b[at + 3]};
  };
  return {u32(16), u32(20)};
}

/** The errors pcl_phaser_optimize --reference printed into \a log, NaN if none. */
inline std::pair<double, double> printedErrors(const std::string& log)
{
  std::ifstream in(log);
  double before = std::nan(""), after = std::nan("");
  for (std::string line; std::getline(in, line);)
    std::sscanf(line.c_str(),
                "trajectory error against the reference: %lf m before, %lf m after",
                &before, &after);
  return {before, after};
}

inline void writePoses(const std::string& path,
                       const std::vector<Eigen::Matrix4d>& poses)
{
  std::ofstream out(path);
  out.precision(17);
  for (const Eigen::Matrix4d& T : poses)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        out << T(r, c) << (r == 2 && c == 3 ? "\n" : " ");
}

/** A 40 m square walked in 20 steps (yaw 90 deg at each corner). */
inline std::vector<Eigen::Matrix4d> square()
{
  std::vector<Eigen::Matrix4d> truth;
  for (int k = 0; k < 20; ++k) {
    Eigen::Matrix4d T = yaw(90.0 * (k / 5));
    const double s = 2.0 * (k % 5);
    const Eigen::Vector2d corner[4] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    const Eigen::Vector2d dir = T.topLeftCorner<2, 2>() * Eigen::Vector2d(1, 0);
    T.topRightCorner<2, 1>() = corner[k / 5] + s * dir;
    truth.push_back(T);
  }
  return truth;
}

/** The square's graph in \a folder/square.g2o: vertices and odometry edges (0.1 m,
 *  3 deg) from \a start's poses, an exact loop edge from every pose to the one 7 steps
 *  on and from start to end; the truth in \a folder/truth.txt. */
inline void writeSquareGraph(const std::string& folder,
                             const std::vector<Eigen::Matrix4d>& start)
{
  const std::vector<Eigen::Matrix4d> truth = square();
  std::ofstream g2o(folder + "/square.g2o");
  g2o << batch::g2oGraph({}, start, batch::OdometrySigma{0.1, 3.0});
  g2o << loopEdge(0, 19, truth) << "\n";
  for (int k = 0; k < 20; ++k)
    g2o << loopEdge(k, (k + 7) % 20, truth) << "\n";
  writePoses(folder + "/truth.txt", truth);
}

} // namespace pose_graph_test
