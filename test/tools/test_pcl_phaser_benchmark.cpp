/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_benchmark: its evaluation protocol (errors, perturbations, conditions) and
 * the built binary on one scan of ../shared/data (skipped with a message when absent).
 */
#include "../registration/test_data.h"
#include "protocol.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace {

using namespace pcl_phaser::bench;

Cloud ring(int n, double radius)
{
  Cloud cloud;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * (i + 0.5) / n;
    PointT p;
    p.x = static_cast<float>(radius * std::cos(a));
    p.y = static_cast<float>(radius * std::sin(a));
    p.z = 0.0f;
    p.intensity = 100.0f;
    cloud.push_back(p);
  }
  return cloud;
}

TEST(EvaluationProtocol, ErrorsOfKnownPoses)
{
  Eigen::Matrix4d truth = Eigen::Matrix4d::Identity(), estimate = truth;
  estimate.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(10.0 * M_PI / 180.0, Eigen::Vector3d(1, 2, 3).normalized())
          .toRotationMatrix();
  estimate.topRightCorner<3, 1>() << 0.3, 0.0, -0.4;
  EXPECT_NEAR(rreDeg(estimate, truth), 10.0, 1e-9);
  EXPECT_NEAR(rreDeg(truth, estimate), 10.0, 1e-9);
  EXPECT_NEAR(rteM(estimate, truth), 0.5, 1e-12);
}

TEST(EvaluationProtocol, RandomPosesAreRotationsInsideTheBall)
{
  std::mt19937 rng(5);
  for (int k = 0; k < 100; ++k) {
    const Eigen::Matrix4d T = randomPose(rng, 2.0);
    const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
    EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
    EXPECT_LE((T.topRightCorner<3, 1>().norm()), 2.0);
  }
  std::mt19937 a(9), b(9);
  EXPECT_EQ(randomPose(a, 1.0), randomPose(b, 1.0)); // deterministic per seed
}

TEST(EvaluationProtocol, ParsesConditionsAndRejectsBadOnes)
{
  Condition c;
  ASSERT_TRUE(parseCondition("noise:40", c));
  EXPECT_EQ(c.kind, Condition::Kind::Noise);
  EXPECT_EQ(c.label(), "PSNR 40 dB");
  ASSERT_TRUE(parseCondition("overlap:0.25", c));
  EXPECT_EQ(c.sweep(), "overlap");
  ASSERT_TRUE(parseCondition("clean", c));
  EXPECT_EQ(c.kind, Condition::Kind::Clean);
  for (const char* bad : {"", "noise", "noise:", "noise:abc", "sparsity:0",
                          "sparsity:1.5", "overlap:-1", "blur:3", "noise:40x"})
    EXPECT_FALSE(parseCondition(bad, c)) << bad;
}

TEST(EvaluationProtocol, NoiseFollowsThePsnrDefinition)
{
  // Range peak 50 m at PSNR 40 dB: sigma = 50 / 100 = 0.5 m; intensity peak 100: 1.
  Cloud cloud = ring(20000, 50.0);
  const Cloud clean = cloud;
  std::mt19937 rng(3);
  applyCondition({Condition::Kind::Noise, 40.0}, cloud, rng);
  double sum_xyz = 0.0, sum_i = 0.0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    sum_xyz += (cloud[i].getVector3fMap() - clean[i].getVector3fMap()).squaredNorm();
    sum_i += std::pow(cloud[i].intensity - clean[i].intensity, 2);
  }
  EXPECT_NEAR(std::sqrt(sum_xyz / (3.0 * cloud.size())), 0.5, 0.01);
  EXPECT_NEAR(std::sqrt(sum_i / cloud.size()), 1.0, 0.02);
}

TEST(EvaluationProtocol, SparsityAndOverlapKeepTheRequestedFraction)
{
  std::mt19937 rng(4);
  for (double keep : {0.5, 0.25, 0.1}) {
    Cloud sparse = ring(40000, 10.0), sector = sparse;
    applyCondition({Condition::Kind::Sparsity, keep}, sparse, rng);
    applyCondition({Condition::Kind::Overlap, keep}, sector, rng);
    EXPECT_NEAR(sparse.size() / 40000.0, keep, 0.01) << keep;
    EXPECT_NEAR(sector.size() / 40000.0, keep, 0.001) << keep;
    // a sector: every kept point within keep * 180 deg of the sector's mean direction
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto& p : sector)
      mean += Eigen::Vector2d(p.x, p.y).normalized();
    mean.normalize();
    for (const auto& p : sector)
      EXPECT_GE(Eigen::Vector2d(p.x, p.y).normalized().dot(mean),
                std::cos(keep * M_PI) - 1e-6);
  }
}

TEST(EvaluationProtocol, QuantilesInterpolate)
{
  EXPECT_DOUBLE_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(median({4.0, 1.0, 2.0, 3.0}), 2.5);
  EXPECT_DOUBLE_EQ(quantile({0.0, 10.0}, 0.9), 9.0);
  EXPECT_TRUE(std::isnan(median({})));
}

std::string run(const std::string& arguments, int& status)
{
  const std::string command = std::string(PCL_PHASER_BENCHMARK_BIN) + " " + arguments;
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[4096];
  while (pipe && std::fgets(buffer, sizeof(buffer), pipe))
    out += buffer;
  status = pipe ? pclose(pipe) : -1;
  return out;
}

TEST(PclPhaserBenchmark, RejectsBadOptions)
{
  int status = 0;
  for (const char* bad : {"-methods nope", "-study x", "-conditions noise:abc",
                          "-poses 0", "-bandwidths 1000", "-scans mars"}) {
    run(std::string(bad) + " 2>&1", status);
    EXPECT_NE(status, 0) << bad;
  }
  run("-data /nonexistent -poses 1 2>&1", status);
  EXPECT_NE(status, 0);
}

TEST(PclPhaserBenchmark, ComparesPhaserWithSacIaOnARealScan)
{
  PCL_PHASER_REQUIRE_DATA("lidar/kitti_synthetic_gt/cloud049.ply");
  const std::string csv = ::testing::TempDir() + "/pcl_phaser_benchmark.csv";
  int status = 0;
  const std::string md = run(
      "-data " + pcl_phaser::test::dataDir() +
          " -scans kitti_synthetic -poses 2 -methods phaser,phaser_xyz,sacia -csv " +
          csv + " 2>/dev/null",
      status);
  ASSERT_EQ(status, 0) << md;
  EXPECT_NE(md.find("| clean | phaser | 2 | 100 % |"), std::string::npos) << md;
  EXPECT_NE(md.find("| clean | sacia | 2 |"), std::string::npos) << md;
  std::ifstream in(csv);
  std::string line;
  int rows = 0;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("set,sweep,value,pose,method", 0), 0u);
  while (std::getline(in, line))
    ++rows;
  EXPECT_EQ(rows, 6); // 2 poses x 3 methods
}

} // namespace
