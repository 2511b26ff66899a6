/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Verification both ways, its rank and limits, and the rank difference's error.
 */
#include "index/point_index.h"
#include "point_test_support.h"
#include "verification/pose_verifier.h"
#include "verification/ranking.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <random>

using namespace pcl::phaser;

namespace {

using test::randomPoints;

TEST(Ranking, RankIsTheScoreLessSixTimesBothViolations)
{
  Verification v;
  v.score = 0.5;
  v.free_space_violation = 0.01;
  v.reverse_free_space_violation = 0.02;
  EXPECT_DOUBLE_EQ(ranked(v).rank, 0.5 - kViolationWeight * 0.03);
  EXPECT_EQ(ranked(v).score, v.score);
}

TEST(Ranking, LimitsNeedInliersConstraintAndNeitherViolation)
{
  VerificationLimits limits;
  Verification v;
  EXPECT_TRUE(meetsLimits(v, limits)); // the defaults limit nothing
  limits.min_inlier_fraction = 0.2;
  limits.min_constraint = 0.04;
  limits.max_free_space_violation = 0.02;
  v.inlier_fraction = 0.3;
  v.constraint = 0.05;
  EXPECT_TRUE(meetsLimits(v, limits));
  v.reverse_free_space_violation = 0.03;
  EXPECT_FALSE(meetsLimits(v, limits));
  v.reverse_free_space_violation = 0.0;
  v.constraint = 0.03;
  EXPECT_FALSE(meetsLimits(v, limits));
}

TEST(PoseVerifier, BothWaysAddsTheReverseViolationOnlyWithFreeSpaces)
{
  const Eigen::Matrix3Xd target = randomPoints(4000, 10.0, 1);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(1.0, -0.5, 0.2);
  const Eigen::Matrix3Xd source = R.transpose() * (target.colwise() - t);
  const PointIndex index(target, 0.3);
  const VerificationSamples samples{source, Eigen::VectorXd::Ones(source.cols()), {}};
  const Eigen::VectorXd target_weights = Eigen::VectorXd::Ones(target.cols());
  const FreeSpace target_seen = freeSpace(target, 32, 0.5);
  const FreeSpace source_seen = freeSpace(source, 32, 0.5);
  VerificationClouds clouds;
  clouds.target = &index;
  clouds.samples = &samples;
  clouds.polish = &samples;
  clouds.target_samples = &target;
  clouds.target_weights = &target_weights;
  const RigidPose pose{R, t + Eigen::Vector3d(0.1, 0.0, 0.0)};
  const Verification one_way = verifyBothWays(clouds, pose, 1);
  const Verification expected = ranked(verifyPose(index, samples, pose.R, pose.t));
  EXPECT_EQ(one_way.score, expected.score);
  EXPECT_EQ(one_way.rank, expected.rank);
  EXPECT_EQ(one_way.reverse_free_space_violation, 0.0);
  clouds.target_free_space = &target_seen;
  clouds.source_free_space = &source_seen;
  const Verification both = verifyBothWays(clouds, pose, 2);
  EXPECT_EQ(
      both.free_space_violation,
      verifyPose(index, samples, pose.R, pose.t, 1, &target_seen).free_space_violation);
  EXPECT_EQ(both.reverse_free_space_violation,
            freeSpaceViolation(source_seen, target, target_weights, R.transpose(),
                               -(R.transpose() * pose.t)));
  EXPECT_EQ(both.rank, ranked(both).rank);
  // A pose against itself differs by nothing, with free spaces or without.
  EXPECT_EQ(rankDifferenceError(clouds, pose, pose, 0.0, 1), 0.0);
  clouds.target_free_space = clouds.source_free_space = nullptr;
  EXPECT_EQ(rankDifferenceError(clouds, pose, pose, 2.0, 1), 0.0);
  EXPECT_GT(rankDifferenceError(clouds, {R, t}, pose, 2.0, 1), 0.0);
}

} // namespace
