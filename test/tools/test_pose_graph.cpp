/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The pose graph of pcl_phaser_batch --g2o --odometry optimized (tools/pose_graph.h):
 * g2o's conventions as the batch writes them, a drifted loop corrected, bad files
 * refused, --drift, the gnuplot top view (--png) and its absence; then end to end on
 * the shared handheld scans: poses made to drift before the batch with --odometry, or
 * the dataset's poses and pcl_phaser_optimize --drift.
 */
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
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <utility>
#include <vector>

namespace {

namespace batch = pcl::phaser::batch;
namespace graph = pcl::phaser::graph;

std::string freshFolder()
{
  char name[] = "/tmp/pcl_phaser_pose_graph_XXXXXX";
  return ::mkdtemp(name) ? name : "/tmp";
}

/** A yaw of \a deg degrees. */
Eigen::Matrix4d yaw(double deg)
{
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
  return T;
}

/** \a truth's odometry with a heading bias of \a bias_deg per step before each move and
 *  its translations scaled by \a scale, from truth[0]. */
std::vector<Eigen::Matrix4d> drifted(const std::vector<Eigen::Matrix4d>& truth,
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

std::map<int, Eigen::Isometry3d> byId(const std::vector<Eigen::Matrix4d>& poses)
{
  std::map<int, Eigen::Isometry3d> out;
  for (std::size_t i = 0; i < poses.size(); ++i)
    out[static_cast<int>(i)] = Eigen::Isometry3d(poses[i]);
  return out;
}

/** An EDGE_SE3:QUAT i j measuring T_i^-1 T_j of \a truth, information 1e4 / 1e6. */
std::string loopEdge(int i, int j, const std::vector<Eigen::Matrix4d>& truth)
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
int exitCode(int status)
{
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/** Whether an executable \a program is on PATH. */
bool onPath(const std::string& program)
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
std::pair<long, long> pngSize(const std::string& path)
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
std::pair<double, double> printedErrors(const std::string& log)
{
  std::ifstream in(log);
  double before = std::nan(""), after = std::nan("");
  for (std::string line; std::getline(in, line);)
    std::sscanf(line.c_str(),
                "trajectory error against the reference: %lf m before, %lf m after",
                &before, &after);
  return {before, after};
}

void writePoses(const std::string& path, const std::vector<Eigen::Matrix4d>& poses)
{
  std::ofstream out(path);
  out.precision(17);
  for (const Eigen::Matrix4d& T : poses)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        out << T(r, c) << (r == 2 && c == 3 ? "\n" : " ");
}

/** A 40 m square walked in 20 steps (yaw 90 deg at each corner). */
std::vector<Eigen::Matrix4d> square()
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
void writeSquareGraph(const std::string& folder,
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

} // namespace

// A 40 m square walked in 20 steps, its odometry drifting 3 deg and 5 % a step, and an
// exact loop edge from every pose to the one 7 steps on (and start to end), the
// odometry weighted as it drifts (0.1 m, 3 deg): the
// optimized trajectory lies on the truth within 2 cm where the drifted one is 1.6 m
// off.
TEST(PoseGraph, DriftedSquareLoopIsCorrected)
{
  const std::vector<Eigen::Matrix4d> truth = square();
  const std::string folder = freshFolder();
  writeSquareGraph(folder, drifted(truth, 3.0, 1.05));
  graph::PoseGraph g;
  ASSERT_EQ(graph::readG2o(folder + "/square.g2o", g), "");
  EXPECT_EQ(g.vertices.size(), 20u);
  EXPECT_EQ(g.edges.size(), 40u);
  EXPECT_EQ(g.fixed, std::set<int>{0});
  const double before = graph::trajectoryError(g.vertices, byId(truth));
  ASSERT_EQ(graph::optimize(g, graph::Loss::Huber), "");
  const double after = graph::trajectoryError(g.vertices, byId(truth));
  std::printf("  square: %.3f m before, %.4f m after\n", before, after);
  EXPECT_GT(before, 1.5);
  EXPECT_LT(after, 0.02);
  // The fixed vertex stays where it was, and the poses file has 12 numbers a line.
  EXPECT_TRUE(g.vertices.at(0).matrix().isApprox(truth[0], 1e-12));
  std::istringstream lines(graph::posesText(g));
  std::string line;
  std::getline(lines, line);
  std::istringstream numbers(line);
  int count = 0;
  for (double v; numbers >> v;)
    ++count;
  EXPECT_EQ(count, 12);
  std::filesystem::remove_all(folder);
}

// An edge written as the batch writes it (T_i^-1 T_j, qx qy qz qw) pulls a vertex
// started 1 m and 20 deg off onto the pose it measures.
TEST(PoseGraph, EdgeMeasuresTheSecondVertexInTheFirstsFrame)
{
  std::vector<Eigen::Matrix4d> truth = {yaw(30.0), yaw(-50.0)};
  truth[0].topRightCorner<3, 1>() << 1.0, 2.0, 0.5;
  truth[1].topRightCorner<3, 1>() << -3.0, 4.0, 1.0;
  std::vector<Eigen::Matrix4d> start = truth;
  start[1] = truth[1] * yaw(20.0);
  start[1](0, 3) += 1.0;
  const std::string folder = freshFolder();
  std::ofstream(folder + "/pair.g2o")
      << batch::g2oVertex(0, start[0]) << "\n"
      << batch::g2oVertex(1, start[1]) << "\n"
      << batch::g2oOdometryEdge(0, truth[0], truth[1], {0.01, 0.1}) << "\n";
  graph::PoseGraph g;
  ASSERT_EQ(graph::readG2o(folder + "/pair.g2o", g), "");
  ASSERT_EQ(graph::optimize(g, graph::Loss::None), ""); // no FIX: the first is held
  EXPECT_TRUE(g.vertices.at(1).matrix().isApprox(truth[1], 1e-6))
      << g.vertices.at(1).matrix();
  std::filesystem::remove_all(folder);
}

TEST(PoseGraph, MalformedFilesAreRefusedWithTheReason)
{
  const std::string folder = freshFolder();
  const auto refuse = [&](const std::string& text, const std::string& reason) {
    std::ofstream(folder + "/bad.g2o") << text;
    graph::PoseGraph g;
    const std::string error = graph::readG2o(folder + "/bad.g2o", g);
    EXPECT_NE(error.find(reason), std::string::npos) << text << " -> " << error;
  };
  const std::string v0 = "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n";
  refuse("", "no vertex");
  refuse("VERTEX_SE3:QUAT 0 0 0\n", "line 1");
  refuse(v0 + v0, "line 2");
  refuse(v0 + "EDGE_SE3:QUAT 0 1 0 0 0 0 0 0 1" + std::string(21 * 2, ' ') + "\n",
         "line 2");
  refuse(v0 + "FIX 3\n", "FIX 3");
  refuse(v0 + "EDGE_SE2 0 1 0 0 0\n", "not a VERTEX_SE3:QUAT");
  std::string edge = "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1";
  for (int k = 0; k < 21; ++k)
    edge += k == 0 || k == 6 || k == 11 || k == 15 || k == 18 || k == 20 ? " 1" : " 0";
  refuse(v0 + edge + "\n", "missing vertex");
  std::string self =
      "EDGE_SE3:QUAT 0 0" + edge.substr(std::string("EDGE_SE3:QUAT 0 1").size());
  refuse(v0 + self + "\n", "line 2"); // a self-loop, its information positive definite
  std::string singular = "EDGE_SE3:QUAT 0 0 1 0 0 0 0 0 1";
  for (int k = 0; k < 21; ++k)
    singular += " 0";
  refuse(v0 + singular + "\n", "positive definite");
  graph::PoseGraph g;
  EXPECT_NE(graph::readG2o(folder + "/none.g2o", g).find("cannot read"),
            std::string::npos);
  std::filesystem::remove_all(folder);
}

// End to end on the shared handheld sequence (30 scans, 74 m walked): its poses made to
// drift 1.5 deg of heading and 5 % of scale a step, loop-closure candidates within 8 m
// of the drifted poses, the batch with --odometry, pcl_phaser_optimize: the trajectory
// error against the dataset's poses (themselves drifting about 0.2 m) falls below 0.25
// m and 0.2x the drifted one.
TEST(LoopClosures, DriftedHandheldTrajectoryIsCorrected)
{
  PCL_PHASER_REQUIRE_DATA("lidar/balm_handheld/poses_T_world_lidar.txt");
  const std::string folder_in = pcl::phaser::test::dataPath("lidar/balm_handheld");
  std::vector<Eigen::Matrix4d> truth;
  ASSERT_EQ(batch::readPoses(folder_in + "/poses_T_world_lidar.txt", truth), "");
  ASSERT_EQ(truth.size(), 30u);
  const std::string folder = freshFolder();
  {
    std::ofstream scans(folder + "/scans.txt"), poses(folder + "/drifted.txt");
    poses.precision(17);
    for (std::size_t i = 0; i < truth.size(); ++i)
      scans << folder_in << "/full" << 6 * i << ".pcd\n";
    for (const Eigen::Matrix4d& T : drifted(truth, 1.5, 1.05)) {
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c)
          poses << T(r, c) << (r == 2 && c == 3 ? "\n" : " ");
    }
  }
  const std::string run = std::string(PCL_PHASER_BATCH_BIN) + " --scans " + folder +
                          "/scans.txt --poses " + folder + "/drifted.txt --radius 8 " +
                          "--min-gap 8 --out " + folder + "/loops.jsonl --g2o " +
                          folder + "/loops.g2o --odometry 2> " + folder + "/batch.log";
  ASSERT_EQ(std::system(run.c_str()), 0) << run;
  const std::string png =
      onPath("gnuplot") ? " --png " + folder + "/trajectory.png" : "";
  const std::string optimize = std::string(PCL_PHASER_OPTIMIZE_BIN) + " " + folder +
                               "/loops.g2o " + folder + "/optimized.txt" + png + " > " +
                               folder + "/optimize.log";
  ASSERT_EQ(std::system(optimize.c_str()), 0) << optimize;
  std::vector<Eigen::Matrix4d> optimized, before;
  ASSERT_EQ(batch::readPoses(folder + "/optimized.txt", optimized), "");
  ASSERT_EQ(batch::readPoses(folder + "/drifted.txt", before), "");
  graph::PoseGraph g;
  ASSERT_EQ(graph::readG2o(folder + "/loops.g2o", g), "");
  int loops = 0;
  for (const graph::Edge& e : g.edges)
    loops += !e.odometry;
  const double drift = graph::trajectoryError(byId(before), byId(truth));
  const double after = graph::trajectoryError(byId(optimized), byId(truth));
  std::printf("  %d loop edges; trajectory error %.3f m drifted, %.3f m optimized\n",
              loops, drift, after);
  EXPECT_GE(loops, 10);
  EXPECT_LT(after, 0.25);
  EXPECT_LT(after, 0.2 * drift);
  if (!png.empty()) {
    EXPECT_EQ(pngSize(folder + "/trajectory.png"), std::make_pair(900L, 900L));
  }
  std::filesystem::remove_all(folder);
}

// The README's example: the batch on the dataset's own poses (candidates within 8 m,
// --odometry), then pcl_phaser_optimize --drift 1.5,0.05 --reference with those poses:
// the drifted start is over 1 m off, the optimized trajectory under 0.25 m and 0.2x
// that.
TEST(LoopClosures, DriftOptionShowsTheHandheldCorrection)
{
  PCL_PHASER_REQUIRE_DATA("lidar/balm_handheld/poses_T_world_lidar.txt");
  const std::string folder_in = pcl::phaser::test::dataPath("lidar/balm_handheld");
  const std::string folder = freshFolder(),
                    poses = folder_in + "/poses_T_world_lidar.txt";
  {
    std::ofstream scans(folder + "/scans.txt");
    for (int i = 0; i < 30; ++i)
      scans << folder_in << "/full" << 6 * i << ".pcd\n";
  }
  const std::string run = std::string(PCL_PHASER_BATCH_BIN) + " --scans " + folder +
                          "/scans.txt --poses " + poses + " --radius 8 --min-gap 8 " +
                          "--out " + folder + "/loops.jsonl --g2o " + folder +
                          "/loops.g2o --odometry 2> " + folder + "/batch.log";
  ASSERT_EQ(exitCode(std::system(run.c_str())), 0) << run;
  const std::string png =
      onPath("gnuplot") ? " --png " + folder + "/trajectory.png" : "";
  const std::string optimize = std::string(PCL_PHASER_OPTIMIZE_BIN) + " " + folder +
                               "/loops.g2o " + folder + "/optimized.txt --drift " +
                               "1.5,0.05 --reference " + poses + png + " > " + folder +
                               "/optimize.log";
  ASSERT_EQ(exitCode(std::system(optimize.c_str())), 0) << optimize;
  const auto [before, after] = printedErrors(folder + "/optimize.log");
  std::printf("  --drift 1.5,0.05: %.3f m before, %.3f m after\n", before, after);
  EXPECT_GT(before, 1.0);
  EXPECT_LT(after, 0.25);
  EXPECT_LT(after, 0.2 * before);
  if (!png.empty()) {
    EXPECT_EQ(pngSize(folder + "/trajectory.png"), std::make_pair(900L, 900L));
  }
  std::filesystem::remove_all(folder);
}

// The reference-free check of the loop edges' covariances on the shared handheld
// sequence: every candidate within 12 m and 4 scans apart (by the dataset's poses), and
// every triangle of converged edges: the closures' NEES follows chi-square(6) closely
// enough (within the 95 % bound for 90-99.5 % of them, mean 2-8).
TEST(LoopClosures, TrianglesCloseWithinTheirCovariances)
{
  PCL_PHASER_REQUIRE_DATA("lidar/balm_handheld/poses_T_world_lidar.txt");
  const std::string folder_in = pcl::phaser::test::dataPath("lidar/balm_handheld");
  const std::string folder = freshFolder();
  {
    std::ofstream scans(folder + "/scans.txt");
    for (int i = 0; i < 30; ++i)
      scans << folder_in << "/full" << 6 * i << ".pcd\n";
  }
  const std::string run = std::string(PCL_PHASER_BATCH_BIN) + " --scans " + folder +
                          "/scans.txt --poses " + folder_in +
                          "/poses_T_world_lidar.txt --radius 12 --min-gap 4 --out " +
                          folder + "/loops.jsonl 2> " + folder + "/batch.log";
  ASSERT_EQ(std::system(run.c_str()), 0) << run;
  std::vector<batch::Record> records;
  ASSERT_EQ(batch::readRecords(folder + "/loops.jsonl", records, false), "");
  const std::vector<batch::Closure> closures = batch::loopClosures(records);
  std::printf("  %zu edges: %s\n", records.size(),
              batch::closureSummary(closures).c_str());
  ASSERT_GE(closures.size(), 200u);
  double sum = 0.0;
  std::size_t within = 0;
  for (const batch::Closure& c : closures) {
    sum += c.nees;
    within += c.nees <= batch::kChiSquare6Bound95;
  }
  const double n = static_cast<double>(closures.size());
  EXPECT_GE(within / n, 0.90) << "the covariances are overconfident";
  EXPECT_LE(within / n, 0.995) << "the covariances are too wide";
  EXPECT_GE(sum / n, 2.0);
  EXPECT_LE(sum / n, 8.0);
  std::filesystem::remove_all(folder);
}

// pcl_phaser_optimize on bad input: a message and the documented exit code.
TEST(PoseGraph, OptimizerExitCodes)
{
  const std::string folder = freshFolder();
  const std::string bin = PCL_PHASER_OPTIMIZE_BIN;
  const auto code = [&](const std::string& args) {
    const int status = std::system((bin + " " + args + " 2> /dev/null").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  EXPECT_EQ(code(""), 1);
  EXPECT_EQ(code(folder + "/g.g2o"), 1);
  EXPECT_EQ(code(folder + "/g.g2o " + folder + "/o.txt --loss squared"), 1);
  EXPECT_EQ(code(folder + "/none.g2o " + folder + "/o.txt"), 2);
  std::ofstream(folder + "/g.g2o") << "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nFIX 0\n";
  EXPECT_EQ(
      code(folder + "/g.g2o " + folder + "/o.txt --reference " + folder + "/none.txt"),
      2);
  EXPECT_EQ(code(folder + "/g.g2o /nonexistent/o.txt"), 3);
  EXPECT_EQ(code(folder + "/g.g2o " + folder + "/o.txt"), 0);
  std::filesystem::remove_all(folder);
}

// --drift on a graph made from the true poses gives the drifted odometry of the square
// test (edges and chained poses, to rounding), and needs an edge from each vertex to
// the next.
TEST(PoseGraph, DriftOdometryChainsDriftedEdgesFromTheFirstVertex)
{
  const std::vector<Eigen::Matrix4d> truth = square();
  const std::string folder = freshFolder();
  writeSquareGraph(folder, truth);
  graph::PoseGraph g, expected;
  ASSERT_EQ(graph::readG2o(folder + "/square.g2o", g), "");
  ASSERT_EQ(graph::driftOdometry(g, 3.0, 0.05), "");
  writeSquareGraph(folder, drifted(truth, 3.0, 1.05));
  ASSERT_EQ(graph::readG2o(folder + "/square.g2o", expected), "");
  for (const auto& [id, T] : expected.vertices)
    EXPECT_TRUE(g.vertices.at(id).matrix().isApprox(T.matrix(), 1e-9)) << id;
  ASSERT_EQ(g.edges.size(), expected.edges.size());
  for (std::size_t k = 0; k < g.edges.size(); ++k) {
    EXPECT_TRUE(g.edges[k].translation.isApprox(expected.edges[k].translation, 1e-9));
    EXPECT_NEAR(g.edges[k].rotation.angularDistance(expected.edges[k].rotation), 0.0,
                1e-9);
  }
  graph::PoseGraph gap;
  gap.vertices = {{0, Eigen::Isometry3d::Identity()},
                  {2, Eigen::Isometry3d::Identity()}};
  EXPECT_NE(graph::driftOdometry(gap, 1.0, 0.0).find("vertex 0"), std::string::npos);
  std::filesystem::remove_all(folder);
}

// pcl_phaser_optimize --drift 3,0.05 --reference on the square made from its true
// poses: the drifted start is 1.5 m and more off, the optimized trajectory within 2 cm.
TEST(PoseGraph, OptimizerDriftOptionStartsDriftedAndCorrectsIt)
{
  const std::string folder = freshFolder();
  writeSquareGraph(folder, square());
  const std::string run = std::string(PCL_PHASER_OPTIMIZE_BIN) + " " + folder +
                          "/square.g2o " + folder + "/o.txt --reference " + folder +
                          "/truth.txt --drift 3,0.05 > " + folder + "/log.txt";
  ASSERT_EQ(exitCode(std::system(run.c_str())), 0) << run;
  const auto [before, after] = printedErrors(folder + "/log.txt");
  std::printf("  --drift 3,0.05: %.3f m before, %.3f m after\n", before, after);
  EXPECT_GT(before, 1.5);
  EXPECT_LT(after, 0.02);
  const auto code = [&](const std::string& drift) {
    return exitCode(std::system((std::string(PCL_PHASER_OPTIMIZE_BIN) + " " + folder +
                                 "/square.g2o " + folder + "/o.txt --drift " + drift +
                                 " 2> /dev/null")
                                    .c_str()));
  };
  EXPECT_EQ(code("1.5"), 1);
  EXPECT_EQ(code("1.5,x"), 1);
  EXPECT_EQ(code("1.5,-1"), 1);
  EXPECT_EQ(code("1.5,0.05"), 0);
  std::ofstream(folder + "/two.g2o") << "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n"
                                     << "VERTEX_SE3:QUAT 1 1 0 0 0 0 0 1\n";
  EXPECT_EQ(exitCode(std::system((std::string(PCL_PHASER_OPTIMIZE_BIN) + " " + folder +
                                  "/two.g2o " + folder + "/o.txt --drift 1,0 2> " +
                                  folder + "/err.txt")
                                     .c_str())),
            2);
  std::filesystem::remove_all(folder);
}

// --png: a PNG from gnuplot (signature, IHDR 900 x 900), with and without --reference,
// at a path with quotes, spaces and command substitutions that must stay a name.
TEST(PoseGraph, OptimizerDrawsTheTopViewWithGnuplot)
{
  REQUIRE_GNUPLOT();
  const std::string folder = freshFolder();
  writeSquareGraph(folder, square());
  const std::string png = folder + "/it's a \"view\" $(echo x) `echo y`.png";
  std::ofstream(folder + "/name.txt") << png;
  const std::string bin = PCL_PHASER_OPTIMIZE_BIN;
  const std::string args =
      " " + folder + "/square.g2o " + folder + "/o.txt --drift 3,0.05";
  // The odd name goes through xargs -0 (no shell parses it).
  const std::string run = "xargs -0 " + bin + args + " --reference " + folder +
                          "/truth.txt --png < " + folder + "/name.txt > " + folder +
                          "/log.txt 2>&1";
  ASSERT_EQ(exitCode(std::system(run.c_str())), 0) << run;
  EXPECT_EQ(pngSize(png), std::make_pair(900L, 900L)); // at the name, as given
  std::error_code ec;
  EXPECT_GT(std::filesystem::file_size(png, ec), 10000u); // lines, legend, text drawn
  const std::string plain = bin + args + " --png " + folder + "/plain.png";
  ASSERT_EQ(exitCode(std::system(plain.c_str())), 0) << plain;
  const auto [width, height] = pngSize(folder + "/plain.png");
  EXPECT_GE(width, 300);
  EXPECT_LE(width, 4000);
  EXPECT_EQ(height, width);
  std::filesystem::remove_all(folder);
}

// Without gnuplot on PATH, or with a gnuplot that fails, --png ends with exit code 3
// and a message naming the package; the poses are still written, no PNG is.
TEST(PoseGraph, OptimizerWithoutGnuplotExitsWithOutputError)
{
  const std::string folder = freshFolder();
  writeSquareGraph(folder, square());
  std::filesystem::create_directory(folder + "/empty");
  std::filesystem::create_directory(folder + "/failing");
  std::ofstream(folder + "/failing/gnuplot")
      << "#!/bin/sh\necho 'no terminal' >&2\nexit 1\n";
  std::filesystem::permissions(folder + "/failing/gnuplot",
                               std::filesystem::perms::owner_all);
  for (const std::string dir : {"empty", "failing"}) {
    const std::string run = "PATH=" + folder + "/" + dir + " " +
                            PCL_PHASER_OPTIMIZE_BIN + " " + folder + "/square.g2o " +
                            folder + "/o.txt --png " + folder +
                            "/out.png > /dev/null 2> " + folder + "/err.txt";
    EXPECT_EQ(exitCode(std::system(run.c_str())), 3) << run;
    std::ifstream in(folder + "/err.txt");
    const std::string message((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
    EXPECT_NE(message.find("apt-get install gnuplot-nox"), std::string::npos)
        << message;
    EXPECT_NE(message.find(dir == "empty" ? "not found" : "no terminal"),
              std::string::npos)
        << message;
    EXPECT_TRUE(std::filesystem::exists(folder + "/o.txt"));
    EXPECT_FALSE(std::filesystem::exists(folder + "/out.png"));
    std::filesystem::remove(folder + "/o.txt");
  }
  std::filesystem::remove_all(folder);
}
