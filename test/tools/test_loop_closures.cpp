/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_batch --odometry and pcl_phaser_optimize end to end on the shared handheld
 * scans (label slow): poses made to drift before the batch, or the dataset's poses and
 * pcl_phaser_optimize --drift; the loop triangles against their covariances.
 */
#include "pose_graph_test_support.h"

#include <gtest/gtest.h>

using namespace pose_graph_test;

namespace {

/** pcl_phaser_batch on the 30 shared handheld scans (listed into \a folder/scans.txt)
 *  with the poses file \a poses and \a options, its records in \a folder/loops.jsonl
 *  and its log in \a folder/batch.log; true when it exited 0 (else a failure is
 *  recorded with the command). */
bool runHandheldBatch(const std::string& folder, const std::string& poses,
                      const std::string& options)
{
  {
    std::ofstream scans(folder + "/scans.txt");
    for (int i = 0; i < 30; ++i)
      scans << pcl::phaser::test::dataPath("lidar/balm_handheld") << "/full" << 6 * i
            << ".pcd\n";
  }
  const std::string run = std::string(PCL_PHASER_BATCH_BIN) + " --scans " + folder +
                          "/scans.txt --poses " + poses + " " + options + " --out " +
                          folder + "/loops.jsonl 2> " + folder + "/batch.log";
  const int code = exitCode(std::system(run.c_str()));
  EXPECT_EQ(code, 0) << run;
  return code == 0;
}

/** pcl_phaser_optimize on \a folder/loops.g2o into \a folder/optimized.txt with
 *  \a options, its output in \a folder/optimize.log, and --png \a folder/trajectory.png
 *  when gnuplot is on PATH; true when it exited 0 (else a failure is recorded). */
bool runOptimize(const std::string& folder, const std::string& options)
{
  const std::string optimize =
      std::string(PCL_PHASER_OPTIMIZE_BIN) + " " + folder + "/loops.g2o " + folder +
      "/optimized.txt" + options +
      (onPath("gnuplot") ? " --png " + folder + "/trajectory.png" : "") + " > " +
      folder + "/optimize.log";
  const int code = exitCode(std::system(optimize.c_str()));
  EXPECT_EQ(code, 0) << optimize;
  return code == 0;
}

/** The trajectory PNG of runOptimize is 900 x 900 when gnuplot drew it. */
void expectTrajectoryPng(const std::string& folder)
{
  if (onPath("gnuplot")) {
    EXPECT_EQ(pngSize(folder + "/trajectory.png"), std::make_pair(900L, 900L));
  }
}

} // namespace

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
  writePoses(folder + "/drifted.txt", drifted(truth, 1.5, 1.05));
  ASSERT_TRUE(runHandheldBatch(folder, folder + "/drifted.txt",
                               "--radius 8 --min-gap 8 --g2o " + folder +
                                   "/loops.g2o --odometry"));
  ASSERT_TRUE(runOptimize(folder, ""));
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
  expectTrajectoryPng(folder);
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
  ASSERT_TRUE(runHandheldBatch(folder, poses,
                               "--radius 8 --min-gap 8 --g2o " + folder +
                                   "/loops.g2o --odometry"));
  ASSERT_TRUE(runOptimize(folder, " --drift 1.5,0.05 --reference " + poses));
  const auto [before, after] = printedErrors(folder + "/optimize.log");
  std::printf("  --drift 1.5,0.05: %.3f m before, %.3f m after\n", before, after);
  EXPECT_GT(before, 1.0);
  EXPECT_LT(after, 0.25);
  EXPECT_LT(after, 0.2 * before);
  expectTrajectoryPng(folder);
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
  ASSERT_TRUE(runHandheldBatch(folder, folder_in + "/poses_T_world_lidar.txt",
                               "--radius 12 --min-gap 4"));
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
