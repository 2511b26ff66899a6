/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_bench: its evaluation protocol (errors, perturbations, conditions) and
 * the built binary on one scan of ../shared/data (skipped with a message when absent).
 */
#include "../registration/test_data.h"
#include "protocol.h"
#include "revisits.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>

namespace {

using namespace pcl::phaser::bench;

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

TEST(DerivedPairs, ShuffleIsAFixedPermutationPerSeed)
{
  std::mt19937 rng(1);
  for (std::uint32_t n : {1u, 2u, 3u, 7u, 1000u})
    for (int k = 0; k < 100; ++k)
      EXPECT_LT(uniformBelow(rng, n), n);
  auto shuffled = [](unsigned seed) {
    std::vector<int> items(10);
    std::iota(items.begin(), items.end(), 0);
    std::mt19937 r(seed);
    fisherYates(items, r);
    return items;
  };
  std::vector<int> sorted = shuffled(1);
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, std::vector<int>({0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(shuffled(1), shuffled(1));
  EXPECT_NE(shuffled(1), shuffled(2));
  // Pinned: mt19937 is fully specified, so is this on every standard library.
  EXPECT_EQ(shuffled(1), std::vector<int>({2, 9, 6, 4, 0, 3, 1, 7, 8, 5}));
}

/** Scans 0, 6, ..., 174, 1.01 m apart along x (no distance on a bin edge), each yawed
 * by its index in degrees. */
std::vector<ScanPose> lineOfPoses()
{
  std::vector<ScanPose> poses(30);
  for (int k = 0; k < 30; ++k) {
    poses[k].index = 6 * k;
    poses[k].world_lidar.topLeftCorner<3, 3>() =
        Eigen::AngleAxisd(6.0 * k * M_PI / 180.0, Eigen::Vector3d::UnitZ())
            .toRotationMatrix();
    poses[k].world_lidar(0, 3) = 1.01 * k;
  }
  return poses;
}

TEST(DerivedPairs, FollowTheGapDistanceAndExclusionRules)
{
  const std::vector<ScanPose> poses = lineOfPoses();
  std::vector<RevisitPair> listed(1);
  listed[0].source = "/elsewhere/full0.pcd"; // compared by file name
  listed[0].target = "full36.pcd";
  DerivedCounts counts;
  const std::vector<RevisitPair> pairs = derivePairs(poses, listed, 3, 1, &counts);
  // 2 * (30 - d) ordered candidates d = 3..20 steps apart (1.01 d m), less 0 <-> 36
  EXPECT_EQ(counts.candidates,
            (std::array<int, 4>{2 * (27 + 26), 2 * (25 + 24 + 23 + 22 + 21) - 2,
                                2 * (20 + 19 + 18 + 17 + 16),
                                2 * (15 + 14 + 13 + 12 + 11 + 10)}));
  EXPECT_EQ(counts.chosen, (std::array<int, 4>{3, 3, 3, 3}));
  ASSERT_EQ(pairs.size(), 12u);
  std::set<std::pair<std::string, std::string>> seen;
  for (const RevisitPair& p : pairs) {
    const int i = std::stoi(p.source.substr(4)), j = std::stoi(p.target.substr(4));
    EXPECT_GE(std::abs(i - j), 18) << p.source << " " << p.target;
    EXPECT_NEAR(p.dist, 1.01 * std::abs(i - j) / 6.0, 1e-9);
    EXPECT_NEAR(p.rel_rot, std::abs(i - j), 1e-9);
    EXPECT_TRUE(std::isnan(p.overlap));
    const Eigen::Matrix4d truth =
        poses[j / 6].world_lidar.inverse() * poses[i / 6].world_lidar;
    EXPECT_TRUE(p.truth.isApprox(truth, 1e-12));
    EXPECT_FALSE(std::min(i, j) == 0 && std::max(i, j) == 36);
    EXPECT_TRUE(seen.insert({p.target, p.source}).second); // no pair twice either way
    EXPECT_FALSE(seen.count({p.source, p.target}));
  }
  EXPECT_EQ(derivePairs(poses, listed, 3, 1)[5].source, pairs[5].source);
  EXPECT_EQ(derivePairs(poses, listed, 1000, 1).size(),
            counts.candidates[0] / 2u + counts.candidates[1] / 2u +
                counts.candidates[2] / 2u + counts.candidates[3] / 2u);
}

TEST(DerivedPairs, ReproduceTheReferencePosesOfPairsTxt)
{
  PCL_PHASER_REQUIRE_DATA("lidar/balm_handheld/poses_T_world_lidar.txt");
  PCL_PHASER_REQUIRE_DATA("lidar/balm_handheld/pairs.txt");
  const std::string folder = pcl::phaser::test::dataPath("lidar/balm_handheld");
  std::vector<ScanPose> poses;
  std::vector<RevisitPair> listed;
  std::string error;
  ASSERT_TRUE(readScanPoses(folder + "/poses_T_world_lidar.txt", poses, error))
      << error;
  ASSERT_TRUE(readPairs(folder + "/pairs.txt", listed, error)) << error;
  const std::vector<RevisitPair> all = derivePairs(poses, {}, 100000, 1);
  int compared = 0;
  for (const RevisitPair& l : listed)
    for (const RevisitPair& d : all)
      if ((d.source == l.source && d.target == l.target) ||
          (d.source == l.target && d.target == l.source)) {
        const Eigen::Matrix4d truth =
            d.source == l.source ? d.truth : d.truth.inverse();
        EXPECT_LT((truth - l.truth).cwiseAbs().maxCoeff(), 1e-4) << l.source;
        EXPECT_NEAR(d.dist, l.dist, 0.006) << l.source;
        ++compared;
      }
  EXPECT_GT(compared, 0);
  for (const RevisitPair& d : derivePairs(poses, listed, 100000, 1))
    for (const RevisitPair& l : listed)
      EXPECT_FALSE(d.source == l.source && d.target == l.target) << d.source;
}

std::string run(const std::string& arguments, int& status)
{
  const std::string command = std::string(PCL_PHASER_BENCH_BIN) + " " + arguments;
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[4096];
  while (pipe && std::fgets(buffer, sizeof(buffer), pipe))
    out += buffer;
  status = pipe ? pclose(pipe) : -1;
  return out;
}

TEST(DerivedPairs, DriftCorrectionAndFitAreInverse)
{
  EXPECT_EQ(scanIndex("full174.pcd"), 174);
  EXPECT_EQ(scanIndex("/data/x/full0.pcd"), 0);
  for (const char* bad : {"full.pcd", "fullx.pcd", "scan3.pcd", "full3.ply"})
    EXPECT_EQ(scanIndex(bad), -1) << bad;
  std::vector<ScanPose> poses(3);
  for (int k = 0; k < 3; ++k) {
    poses[k].index = 6 * k;
    poses[k].world_lidar.topLeftCorner<3, 3>() =
        Eigen::AngleAxisd(0.7 * k + 0.2, Eigen::Vector3d(1, 2, 3).normalized())
            .toRotationMatrix();
    poses[k].world_lidar.topRightCorner<3, 1>() = Eigen::Vector3d(k, 2.0 * k, 0.5);
  }
  std::vector<RevisitPair> pairs;
  std::vector<Eigen::Matrix4d> estimates;
  const Eigen::Vector3d drift(0.002, -0.001, 0.0005);
  for (int s = 0; s < 3; ++s)
    for (int t = 0; t < 3; ++t) {
      if (s == t)
        continue;
      RevisitPair p;
      p.source = "full" + std::to_string(6 * s) + ".pcd";
      p.target = "full" + std::to_string(6 * t) + ".pcd";
      p.truth = poses[t].world_lidar.inverse() * poses[s].world_lidar;
      pairs.push_back(p);
      RevisitPair corrected = p; // what an exact estimate of the drifted scans gives
      ASSERT_TRUE(correctDrift(corrected, poses, drift));
      const Eigen::Vector3d moved = (corrected.truth - p.truth).topRightCorner<3, 1>();
      EXPECT_NEAR(moved.norm(), std::abs(6.0 * (s - t)) * drift.norm(), 1e-12);
      estimates.push_back(corrected.truth);
    }
  EXPECT_TRUE(fitDrift(pairs, estimates, poses).isApprox(drift, 1e-9));
  RevisitPair unknown = pairs.front();
  unknown.target = "full99.pcd";
  EXPECT_FALSE(correctDrift(unknown, poses, drift));
}

TEST(PclPhaserBenchmark, RejectsBadOptions)
{
  int status = 0;
  for (const char* bad :
       {"", "x", "compare --methods nope", "compare --conditions noise:abc",
        "compare --poses 0", "compare --poses", "compare --poses 1.5",
        "compare --bandwidths 1000", "compare --scans mars", "compare -poses 1",
        "compare --max-tilt 400", "compare --orientation-candidates 99",
        "align --bandwidth 1", "align a.pcd", "speed --threads 2", "yardstick x",
        "region --radius 0"}) {
    const std::string out = run(std::string(bad) + " 2>&1", status);
    EXPECT_NE(status, 0) << bad;
    EXPECT_FALSE(out.empty()) << bad; // a message says why
  }
  run("compare --data /nonexistent --poses 1 2>&1", status);
  EXPECT_NE(status, 0);
}

TEST(PclPhaserBenchmark, PrintsHelpPerSubcommand)
{
  int status = 0;
  const std::string all = run("--help", status);
  EXPECT_EQ(status, 0);
  for (const char* sub :
       {"compare", "nees", "detection", "revisits", "objects", "align", "speed",
        "prior-map", "region", "calibrate-covariance"}) {
    EXPECT_NE(all.find(std::string("  ") + sub + " "), std::string::npos) << sub;
    const std::string help = run(std::string(sub) + " --help", status);
    EXPECT_EQ(status, 0) << sub;
    EXPECT_NE(help.find(std::string("Usage: pcl_phaser_bench ") + sub),
              std::string::npos)
        << help;
  }
  // The engine's settings as the tools spell them, with the subcommand's defaults.
  const std::string align = run("align --help", status);
  EXPECT_NE(align.find("--max-tilt"), std::string::npos) << align;
  EXPECT_NE(align.find("--orientation-candidates"), std::string::npos) << align;
  EXPECT_EQ(run("speed --help", status).find("--max-tilt"), std::string::npos);
}

TEST(PclPhaserBenchmark, ComparesPhaserWithSacIaOnARealScan)
{
  PCL_PHASER_REQUIRE_DATA("lidar/kitti_synthetic_gt/cloud049.ply");
  const std::string csv = ::testing::TempDir() + "/pcl_phaser_benchmark.csv";
  int status = 0;
  const std::string md = run("compare --data " + pcl::phaser::test::dataDir() +
                                 " --scans kitti_synthetic --poses 2 --methods "
                                 "phaser,phaser_xyz,sacia --csv " +
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

TEST(PclPhaserBenchmark, RevisitStudyTabulatesMethodsByDistance)
{
  int status = 0;
  const std::string skipped = run("revisits --data /nonexistent 2>&1", status);
  EXPECT_EQ(status, 0) << skipped; // absent data: a message, not a failure
  EXPECT_NE(skipped.find("not found, skipping"), std::string::npos) << skipped;
  run("revisits --methods nope 2>&1", status);
  EXPECT_NE(status, 0);
  PCL_PHASER_REQUIRE_DATA("lidar/balm_handheld/pairs.txt");
  const std::string md = run("revisits --data " + pcl::phaser::test::dataDir() +
                                 " --methods phaser_xyz --max-pairs 2 2>/dev/null",
                             status);
  ASSERT_EQ(status, 0) << md;
  EXPECT_NE(md.find("| method | distance | n | success @2 m | success @0.6 m |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("Yardstick: one 128^3 real-to-complex FFT"), std::string::npos);
  for (const char* bin :
       {"[0, 5) m", "[5, 10) m", "[10, 15) m", "[15, inf) m", "<10 m", ">=10 m", "all"})
    EXPECT_NE(md.find(std::string("| phaser_xyz | ") + bin + " | "), std::string::npos)
        << bin << "\n"
        << md;
  EXPECT_NE(md.find("| phaser_xyz | all | 2 | "), std::string::npos) << md;
  EXPECT_NE(md.find("| method | stage | median (ms) | median (FFT128) | x phaser_xyz's "
                    "total |"),
            std::string::npos)
      << md;
  for (const char* stage : {"total", "target", "sampling", "so3", "translation",
                            "orientation", "verification"})
    EXPECT_NE(md.find(std::string("| phaser_xyz | ") + stage + " | "),
              std::string::npos)
        << stage;
  EXPECT_NE(
      md.find("| method | distance | converged with covariance | mean NEES (6) |"),
      std::string::npos)
      << md;
  run("revisits --reference-drift 1,2 2>&1", status);
  EXPECT_NE(status, 0);
  run("revisits --derived-pairs -1 2>&1", status);
  EXPECT_NE(status, 0);
  for (const char* wedge : {"0", "1.5", "nan"}) {
    run(std::string("revisits --source-wedge ") + wedge + " 2>&1", status);
    EXPECT_NE(status, 0) << wedge;
  }
  // One pair, range only, with the study's options \a extra.
  const auto one_pair = [&](const std::string& extra) {
    return run("revisits --data " + pcl::phaser::test::dataDir() + " " + extra +
                   " --max-pairs 1 --methods phaser_xyz 2>/dev/null",
               status);
  };
  const std::string wedged = one_pair("--source-wedge 0.5");
  ASSERT_EQ(status, 0) << wedged;
  EXPECT_NE(wedged.find("| phaser_xyz | all | 1 | "), std::string::npos) << wedged;
  const std::string derived = one_pair("--derived-pairs 1");
  ASSERT_EQ(status, 0) << derived;
  EXPECT_NE(derived.find("pairs derived from"), std::string::npos) << derived;
  EXPECT_NE(derived.find("| method | distance | n | success @2 m |"), std::string::npos)
      << derived;
  EXPECT_NE(derived.find("| phaser_xyz | all | 1 | "), std::string::npos) << derived;
}

} // namespace
