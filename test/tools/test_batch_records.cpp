// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file test_batch_records.cpp
 * \brief pcl_phaser_batch's outputs: g2o's conventions (frame, quaternion order,
 * information), records cut short by a kill, and merging shard outputs.
 */
#include "batch_records.h"
#include "result_field_keys.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace batch = pcl::phaser::batch;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using pcl::phaser::test::kResultFieldKeys;
using pcl::phaser::test::kStageKeys;

namespace {

/** The fields of an EDGE_SE3:QUAT line: tag, ids, x y z qx qy qz qw, the information's
 *  upper triangle. */
struct EdgeFields {
  std::string tag;
  int i = -1, j = -1;
  double v[7] = {};
  std::vector<double> upper;
};

EdgeFields parseEdge(const std::string& line)
{
  EdgeFields e;
  std::istringstream in(line);
  in >> e.tag >> e.i >> e.j;
  for (double& value : e.v)
    in >> value;
  for (double value; in >> value;)
    e.upper.push_back(value);
  return e;
}

std::string freshFolder()
{
  char pattern[] = "/tmp/pcl_phaser_batch_test_XXXXXX";
  return ::mkdtemp(pattern);
}

std::string readText(const std::string& path)
{
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

batch::Record convergedRecord(std::size_t index, int target, int source,
                              const Eigen::Matrix4d& T, const Matrix6d& covariance)
{
  batch::Pair pair;
  pair.index = index;
  pair.source = "s" + std::to_string(source);
  pair.target = "t" + std::to_string(target);
  pair.source_id = source;
  pair.target_id = target;
  pcl::phaser::PhaserResult result;
  result.transformation = T;
  result.converged = true;
  result.covariance = covariance;
  return batch::alignedRecord(pair, 3, result, 1.0);
}

/** \brief g2o's EdgeSE3 error of measurement \a Z at the true relative pose: the
 *  translation and the quaternion's x y z (w >= 0) of Z^-1 T_true. */
Eigen::Matrix<double, 6, 1> g2oError(const Eigen::Matrix4d& Z, const Eigen::Matrix4d& T)
{
  const Eigen::Matrix4d delta = Z.inverse() * T;
  Eigen::Quaterniond q(Eigen::Matrix3d(delta.topLeftCorner<3, 3>()));
  if (q.w() < 0)
    q.coeffs() = -q.coeffs();
  Eigen::Matrix<double, 6, 1> e;
  e << delta.topRightCorner<3, 1>(), q.vec();
  return e;
}

} // namespace

TEST(BatchG2o, InformationWeighsG2osErrorAsTheCovarianceWeighsOurs)
{
  Eigen::Matrix4d Z = Eigen::Matrix4d::Identity();
  Z.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(2.1, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).matrix();
  Z.topRightCorner<3, 1>() << 4.0, -7.0, 0.5;
  Matrix6d A = Matrix6d::Random();
  const Matrix6d covariance = 1e-4 * (A * A.transpose() + Matrix6d::Identity());
  const Matrix6d info = batch::g2oInformation(Z, covariance);
  // getCovariance()'s error: omega = Log(R_true R^T), nu = t_true - t (target frame).
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::Matrix<double, 6, 1> x = 1e-4 * Eigen::Matrix<double, 6, 1>::Random();
    Eigen::Matrix4d truth = Z;
    truth.topLeftCorner<3, 3>() =
        Eigen::AngleAxisd(x.head<3>().norm(), x.head<3>().normalized()).matrix() *
        Z.topLeftCorner<3, 3>();
    truth.topRightCorner<3, 1>() += x.tail<3>();
    const Eigen::Matrix<double, 6, 1> e = g2oError(Z, truth);
    const double ours = x.dot(covariance.ldlt().solve(x));
    EXPECT_NEAR(e.dot(info * e), ours, 1e-3 * ours) << trial;
  }
}

TEST(BatchG2o, EdgeLineIsTargetSourceXyzThenQxQyQzQwThenUpperTriangle)
{
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
  T.topRightCorner<3, 1>() << 1.0, 2.0, 3.0;
  const std::string line =
      batch::g2oEdge(convergedRecord(0, 4, 7, T, 0.01 * Matrix6d::Identity()));
  const EdgeFields e = parseEdge(line);
  const std::string& tag = e.tag;
  const int i = e.i, j = e.j;
  const double* v = e.v;
  EXPECT_EQ(tag, "EDGE_SE3:QUAT");
  EXPECT_EQ(i, 4); // the target
  EXPECT_EQ(j, 7); // the source
  EXPECT_DOUBLE_EQ(v[0], 1.0);
  EXPECT_DOUBLE_EQ(v[2], 3.0);
  EXPECT_NEAR(v[3], 0.0, 1e-15);
  EXPECT_NEAR(v[5], std::sqrt(0.5), 1e-15); // qz
  EXPECT_NEAR(v[6], std::sqrt(0.5), 1e-15); // qw last
  const std::vector<double>& upper = e.upper;
  ASSERT_EQ(upper.size(), 21u);
  EXPECT_NEAR(upper[0], 100.0, 1e-9);  // (x, x): 1 / 0.01
  EXPECT_NEAR(upper[15], 400.0, 1e-9); // (qx, qx): 1 / (0.01 / 4)
  EXPECT_NEAR(upper[1], 0.0, 1e-9);
}

TEST(BatchG2o, OdometryEdgesFixTheFirstVertexAndMeasureConsecutivePoses)
{
  std::vector<Eigen::Matrix4d> poses(3, Eigen::Matrix4d::Identity());
  poses[1].topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
  poses[1].topRightCorner<3, 1>() << 1.0, 0.0, 0.0;
  poses[2] = poses[1];
  poses[2].topRightCorner<3, 1>() << 1.0, 2.0, 0.0; // 2 m along vertex 1's x
  const std::string graph = batch::g2oGraph({}, poses, batch::OdometrySigma{0.1, 2.0});
  EXPECT_NE(graph.find("FIX 0\n"), std::string::npos);
  const std::string edge = batch::g2oOdometryEdge(1, poses[1], poses[2], {0.1, 2.0});
  EXPECT_NE(graph.find(edge + "\n"), std::string::npos);
  const EdgeFields e = parseEdge(edge);
  const int i = e.i, j = e.j;
  const double* v = e.v;
  EXPECT_EQ(i, 1);
  EXPECT_EQ(j, 2);
  EXPECT_NEAR(v[0], 2.0, 1e-12); // T_1^-1 T_2: 2 m along x of vertex 1
  EXPECT_NEAR(v[1], 0.0, 1e-12);
  EXPECT_NEAR(v[6], 1.0, 1e-12); // no rotation: qw = 1
  const std::vector<double>& upper = e.upper;
  ASSERT_EQ(upper.size(), 21u);
  EXPECT_NEAR(upper[0], 100.0, 1e-9); // 1 / 0.1^2
  const double r = 2.0 * M_PI / 180.0;
  EXPECT_NEAR(upper[15], 4.0 / (r * r), 1e-6); // g2o's qx is half the angle
  EXPECT_EQ(upper[1], 0.0);
  // Without odometry: no FIX and no edges of its own.
  EXPECT_EQ(batch::g2oGraph({}, poses).find("FIX"), std::string::npos);
}

TEST(BatchG2o, NoEdgeForPairsThatDidNotConvergeOrFailed)
{
  batch::Record r =
      convergedRecord(0, 0, 1, Eigen::Matrix4d::Identity(), Matrix6d::Identity());
  r["converged"] = false;
  EXPECT_EQ(batch::g2oEdge(r), "");
  batch::Pair pair;
  EXPECT_EQ(batch::g2oEdge(batch::failedRecord(pair, 1, "no such file")), "");
  EXPECT_EQ(batch::g2oVertex(3, Eigen::Matrix4d::Identity()),
            "VERTEX_SE3:QUAT 3 0 0 0 0 0 0 1");
}

TEST(BatchRecords, AlignedRecordHasTheKeysOfPclPhaserAlignJson)
{
  batch::Record r =
      convergedRecord(2, 0, 1, Eigen::Matrix4d::Identity(), Matrix6d::Identity());
  std::vector<std::string> keys;
  for (const auto& [key, value] : r.items())
    keys.push_back(key);
  std::vector<std::string> expected = {"pair",   "pairs",          "source",
                                       "target", "source_id",      "target_id",
                                       "status", "transformation", "converged"};
  expected.insert(expected.end(), kResultFieldKeys.begin(), kResultFieldKeys.end());
  expected.push_back("time_ms");
  EXPECT_EQ(keys, expected);
  EXPECT_NE(r.dump().find("\"runner_up_rank\":null"), std::string::npos); // none
  EXPECT_EQ(r["covariance"][5][5], 1.0);
  std::vector<std::string> stages;
  for (const auto& [key, value] : r["stages_ms"].items())
    stages.push_back(key);
  EXPECT_EQ(stages, std::vector<std::string>(kStageKeys.begin(), kStageKeys.end()));
}

TEST(BatchRecords, RunFingerprintKeepsTheFormatOfEarlierRecords)
{
  pcl::phaser::PhaserParameters p;
  const std::string plain = "shard 0/1, B 64, grid 128, voxel 0, passes 3, auto";
  EXPECT_EQ(batch::runFingerprint(p, 0, 1), plain);
  p.num_threads = 7; // results are bit-identical for any count
  EXPECT_EQ(batch::runFingerprint(p, 0, 1), plain);
  p.region = pcl::phaser::Region{1.0, 2.0, 3.0, 4.0};
  p.max_tilt_deg = 10.0;
  p.min_inlier_fraction = 0.3;
  p.projection_center = pcl::phaser::ProjectionCenter::Centroid;
  const std::string priors = "shard 1/4, B 64, grid 128, voxel 0, passes 3, centroid, "
                             "region 1,2,3,4, tilt 10";
  const std::string inliers = ", min_inlier_fraction 0.29999999999999999";
  EXPECT_EQ(batch::runFingerprint(p, 1, 4), priors + inliers);
  // The typed settings, in table order, only when not at their default.
  p.normalized_refinement = false;
  p.channels = pcl::phaser::CHANNEL_RANGE;
  EXPECT_EQ(batch::runFingerprint(p, 1, 4),
            priors + ", normalized_refinement false, channels range" + inliers);
}

TEST(BatchRecords, ALineCutShortByAKillIsCutOffAndAppendingGoesOn)
{
  const std::string folder = freshFolder(), path = folder + "/out.jsonl";
  const batch::Record a =
      convergedRecord(0, 0, 1, Eigen::Matrix4d::Identity(), Matrix6d::Identity());
  const batch::Record b =
      convergedRecord(1, 0, 2, Eigen::Matrix4d::Identity(), Matrix6d::Identity());
  const std::string whole = a.dump() + "\n" + b.dump() + "\n";
  std::ofstream(path) << whole << b.dump().substr(0, 40);
  std::vector<batch::Record> records;
  EXPECT_NE(batch::readRecords(path, records, false).find("cut short"),
            std::string::npos);
  ASSERT_EQ(batch::readRecords(path, records, true), "");
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[1].dump(), b.dump()); // numbers round-trip exactly
  EXPECT_EQ(readText(path), whole);
  {
    batch::RecordWriter writer;
    ASSERT_EQ(writer.open(path), "");
    ASSERT_EQ(writer.append(a), "");
  }
  ASSERT_EQ(batch::readRecords(path, records, false), "");
  EXPECT_EQ(records.size(), 3u);
  std::ofstream(path) << whole << "{not json}\n";
  EXPECT_NE(batch::readRecords(path, records, true).find("line 3"), std::string::npos);
  std::remove(path.c_str());
  ::rmdir(folder.c_str());
}

TEST(BatchMerge, JoinsPartsInPairOrderAndRefusesGapsAndRepeats)
{
  const std::string folder = freshFolder();
  const auto record = [](std::size_t i) {
    return convergedRecord(i, 0, static_cast<int>(i) + 1, Eigen::Matrix4d::Identity(),
                           Matrix6d::Identity())
               .dump() +
           "\n";
  };
  std::ofstream(folder + "/a.jsonl") << record(2) << record(0);
  std::ofstream(folder + "/b.jsonl") << record(1);
  std::ofstream(folder + "/c.jsonl") << record(1);
  const std::string out = folder + "/all.jsonl";
  ASSERT_EQ(batch::mergeParts(out, {folder + "/a.jsonl", folder + "/b.jsonl"}), "");
  EXPECT_EQ(readText(out), record(0) + record(1) + record(2));
  EXPECT_NE(
      batch::mergeParts(out, {folder + "/a.jsonl"}).find("1 of 3 pairs are missing"),
      std::string::npos);
  EXPECT_NE(batch::mergeParts(
                out, {folder + "/a.jsonl", folder + "/b.jsonl", folder + "/c.jsonl"})
                .find("pair 1 is in"),
            std::string::npos);
  std::ofstream(folder + "/a.g2o")
      << "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nEDGE_SE3:QUAT 0 1 x\n";
  std::ofstream(folder + "/b.g2o")
      << "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nEDGE_SE3:QUAT 0 2 y\n";
  ASSERT_EQ(
      batch::mergeParts(folder + "/all.g2o", {folder + "/b.g2o", folder + "/a.g2o"}),
      "");
  EXPECT_EQ(readText(folder + "/all.g2o"),
            "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n"
            "EDGE_SE3:QUAT 0 1 x\nEDGE_SE3:QUAT 0 2 y\n");
  // The same line in two parts (odometry edges, FIX) is kept once; an edge that
  // differs between parts is refused.
  std::ofstream(folder + "/c.g2o") << "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nFIX 0\n"
                                      "EDGE_SE3:QUAT 0 1 x\n";
  ASSERT_EQ(
      batch::mergeParts(folder + "/all.g2o", {folder + "/a.g2o", folder + "/c.g2o"}),
      "");
  EXPECT_EQ(readText(folder + "/all.g2o"),
            "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nFIX 0\nEDGE_SE3:QUAT 0 1 x\n");
  // A loop edge beside the odometry edge of its pair (--min-gap 1) is kept; a third
  // line for one pair means parts of different runs.
  std::ofstream(folder + "/d.g2o") << "EDGE_SE3:QUAT 0 1 z\n";
  std::ofstream(folder + "/e.g2o") << "EDGE_SE3:QUAT 0 1 w\n";
  ASSERT_EQ(
      batch::mergeParts(folder + "/all.g2o", {folder + "/a.g2o", folder + "/d.g2o"}),
      "");
  EXPECT_EQ(readText(folder + "/all.g2o"),
            "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n"
            "EDGE_SE3:QUAT 0 1 x\nEDGE_SE3:QUAT 0 1 z\n");
  EXPECT_NE(batch::mergeParts(folder + "/all.g2o",
                              {folder + "/a.g2o", folder + "/d.g2o", folder + "/e.g2o"})
                .find("differs"),
            std::string::npos);
  EXPECT_NE(batch::mergeParts(out, {folder + "/a.g2o"}).find("not of the kind"),
            std::string::npos);
  EXPECT_NE(batch::mergeParts(out, {folder + "/none.jsonl"}).find("cannot read"),
            std::string::npos);
  std::system(("rm -rf '" + folder + "'").c_str());
}
