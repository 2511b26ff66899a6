/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The pose graph of pcl_phaser_batch --g2o --odometry optimized (tools/pose_graph.h):
 * g2o's conventions as the batch writes them, a drifted loop corrected, bad files
 * refused, --drift, the gnuplot top view (--png) and its absence.
 */
#include "pose_graph_test_support.h"

#include <gtest/gtest.h>

using namespace pose_graph_test;

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
