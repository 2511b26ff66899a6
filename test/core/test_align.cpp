/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The engine's entry point, pcl::phaser::align(): bad input gives a reason instead of a
 * throw or a crash, the guess is composed in the caller's frames, and one Target serves
 * concurrent calls with a single preparation.
 */
#include <pcl_phaser/core/pipeline.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <thread>

namespace {

using pcl::phaser::PhaserParameters;
using pcl::phaser::PhaserResult;

/** Points on the walls, floor and ceiling of a 12 x 8 x 3 m room with a few boxes in
 * it, in the frame of a sensor at its middle. */
Eigen::Matrix3Xd room(int n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3Xd p(3, n);
  const Eigen::Vector3d half(6.0, 4.0, 1.5);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d q(u(rng) * half.x(), u(rng) * half.y(), u(rng) * half.z());
    const int face = i % 8;
    if (face < 6)
      q[face / 2] = (face % 2 ? 1.0 : -1.0) * half[face / 2];
    else // two boxes of 1 m against the walls
      q = Eigen::Vector3d(face == 6 ? 4.0 : -2.0, face == 6 ? -3.0 : 3.0, -1.0) +
          0.5 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    p.col(i) = q;
  }
  return p;
}

PhaserParameters small()
{
  PhaserParameters p;
  p.bandwidth = 16;
  p.spatial_grid_size = 32;
  p.passes = 1;
  return p;
}

void expectFailure(const PhaserResult& r, const Eigen::Matrix4d& guess)
{
  EXPECT_FALSE(r.error.empty());
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(r.transformation == guess);
  EXPECT_TRUE(r.diagnostics.hypotheses.empty());
}

TEST(EngineAlign, BadInputGivesAReason)
{
  const pcl::phaser::Target target(room(2000, 1));
  const pcl::phaser::SourceCloud source{room(2000, 2), {}};
  Eigen::Matrix4d guess = Eigen::Matrix4d::Identity();
  guess(0, 3) = 0.5;
  PhaserParameters bad = small();
  bad.bandwidth = 0;
  expectFailure(pcl::phaser::align(target, source, guess, bad), guess);
  bad = small();
  bad.min_normalized_overlap = std::numeric_limits<double>::quiet_NaN();
  expectFailure(pcl::phaser::align(target, source, guess, bad), guess);
  // A channel on one side only, a channel of the wrong length, no points, a NaN point.
  expectFailure(pcl::phaser::align(target,
                                   {source.points, {Eigen::VectorXd::Ones(2000)}},
                                   guess, small()),
                guess);
  const pcl::phaser::Target short_channel(room(100, 3), {Eigen::VectorXd::Ones(99)});
  expectFailure(pcl::phaser::align(short_channel,
                                   {source.points, {Eigen::VectorXd::Ones(2000)}},
                                   guess, small()),
                guess);
  expectFailure(
      pcl::phaser::align(target, {Eigen::Matrix3Xd(3, 0), {}}, guess, small()), guess);
  const pcl::phaser::Target empty{Eigen::Matrix3Xd(3, 0)};
  expectFailure(pcl::phaser::align(empty, source, guess, small()), guess);
  pcl::phaser::SourceCloud nan = source;
  nan.points(1, 7) = std::numeric_limits<double>::quiet_NaN();
  expectFailure(pcl::phaser::align(target, nan, guess, small()), guess);
  pcl::phaser::SourceCloud far = source;
  far.points(0, 0) = 2e6;
  expectFailure(pcl::phaser::align(target, far, guess, small()), guess);
  // All points at the center: no spherical signal.
  const pcl::phaser::Target point{Eigen::Matrix3Xd::Zero(3, 10)};
  expectFailure(pcl::phaser::align(point, source, guess, small()), guess);
  Eigen::Matrix4d inf = guess;
  inf(2, 3) = std::numeric_limits<double>::infinity();
  const PhaserResult r = pcl::phaser::align(target, source, inf, small());
  EXPECT_FALSE(r.error.empty());
  EXPECT_FALSE(r.converged);
}

TEST(EngineAlign, ComposesTheGuessInTheCallersFrames)
{
  // The source is the target seen from a sensor moved by T; the guess is T itself, so
  // the residual is the identity and the result must be T (to within a voxel).
  const Eigen::Matrix3Xd points = room(6000, 4);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).matrix();
  T.topRightCorner<3, 1>() = Eigen::Vector3d(0.8, -0.3, 0.1);
  const Eigen::Matrix3Xd moved =
      (T.topLeftCorner<3, 3>().transpose() * points).colwise() -
      T.topLeftCorner<3, 3>().transpose() * T.topRightCorner<3, 1>();
  const pcl::phaser::Target target(points);
  PhaserParameters p = small();
  p.projection_center = pcl::phaser::ProjectionCenter::Centroid;
  const PhaserResult r = pcl::phaser::align(target, {moved, {}}, T, p);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.projection_center, pcl::phaser::ProjectionCenter::Centroid);
  EXPECT_LT((r.transformation - T).norm(), 0.5);
  const std::vector<pcl::phaser::Hypothesis>& hypotheses = r.diagnostics.hypotheses;
  ASSERT_FALSE(hypotheses.empty());
  EXPECT_TRUE(hypotheses[r.chosen_hypothesis].transformation.allFinite());
}

TEST(EngineAlign, OneTargetServesConcurrentCalls)
{
  const pcl::phaser::Target target(room(4000, 5));
  const pcl::phaser::SourceCloud source{room(4000, 6), {}};
  PhaserResult results[2];
  std::thread threads[2];
  for (int k = 0; k < 2; ++k)
    threads[k] = std::thread([&, k] {
      results[k] =
          pcl::phaser::align(target, source, Eigen::Matrix4d::Identity(), small());
    });
  for (std::thread& t : threads)
    t.join();
  ASSERT_TRUE(results[0].error.empty()) << results[0].error;
  ASSERT_TRUE(results[1].error.empty()) << results[1].error;
  EXPECT_TRUE(results[0].transformation == results[1].transformation);
  // Prepared once: by whichever call came first.
  EXPECT_EQ((results[0].diagnostics.times.target > 0.0) +
                (results[1].diagnostics.times.target > 0.0),
            1);
}

// A target kept in a frame whose origin is 5 km from its data, turned 35 deg (a map in
// a site frame): about its sensor origin (the default) the pose is the one found in the
// target's own frame, moved by the site transform.
TEST(EngineAlign, FarFrameMatchesLocalFrame)
{
  const Eigen::Matrix3Xd points = room(6000, 4);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).matrix();
  T.topRightCorner<3, 1>() = Eigen::Vector3d(0.8, -0.3, 0.1);
  const pcl::phaser::SourceCloud source{
      (T.topLeftCorner<3, 3>().transpose() * points).colwise() -
          T.topLeftCorner<3, 3>().transpose() * T.topRightCorner<3, 1>(),
      {}};
  Eigen::Matrix4d G = Eigen::Matrix4d::Identity();
  G.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(35.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
  G.topRightCorner<3, 1>() = Eigen::Vector3d(4000.0, -3000.0, 12.0);
  const Eigen::Matrix3Xd far =
      (G.topLeftCorner<3, 3>() * points).colwise() + G.topRightCorner<3, 1>();
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  const PhaserResult local =
      pcl::phaser::align(pcl::phaser::Target(points), source, I, small());
  const PhaserResult moved =
      pcl::phaser::align(pcl::phaser::Target(far), source, I, small());
  ASSERT_TRUE(local.error.empty()) << local.error;
  ASSERT_TRUE(moved.error.empty()) << moved.error;
  EXPECT_EQ(moved.projection_center, pcl::phaser::ProjectionCenter::SensorOrigin);
  EXPECT_LT((local.transformation - T).norm(), 0.3) << local.transformation;
  const Eigen::Matrix4d back = G.inverse() * moved.transformation;
  EXPECT_LT((back - T).norm(), 0.3) << back;
  EXPECT_LT((back - local.transformation).norm(), 0.1) << back - local.transformation;
  EXPECT_EQ(moved.converged, local.converged);
}

} // namespace
