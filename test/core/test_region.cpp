/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The priors' pieces: the crop of the target to a region, the bound on the translation
 * search, and the guard on the answer (a region, a tilt cone).
 */
#include "priors/allowed_poses.h"
#include "priors/region.h"
#include "so3/so3_correlation_grid.h"
#include "support/error.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace pcl::phaser::detail {
namespace {

TEST(Region, CropKeepsThePointsInReachRelativeToTheCenter)
{
  Eigen::Matrix3Xd points(3, 300);
  Eigen::VectorXd intensity(300);
  for (int i = 0; i < 300; ++i) {
    points.col(i) = Eigen::Vector3d(i, 0.0, 1.0); // x = 0 .. 299 m
    intensity(i) = i;
  }
  SearchRegion region;
  region.center = Eigen::Vector3d(100.0, 0.0, 1.0);
  region.radius = 10.0;
  region.reach = 60.0;
  const RegionCloud cloud = cropToRegion(points, {intensity}, region);
  ASSERT_EQ(cloud.points.cols(), 121); // x = 40 .. 160
  EXPECT_EQ(cloud.points.col(0), Eigen::Vector3d(-60.0, 0.0, 0.0));
  ASSERT_EQ(cloud.channels.size(), 1u);
  EXPECT_EQ(cloud.channels[0](0), 40.0);
  EXPECT_EQ(cloud.channels[0](120), 160.0);
  region.center.x() = 1000.0; // no point within reach
  EXPECT_THROW(cropToRegion(points, {intensity}, region), InvalidArgument);
}

TEST(Region, ShiftsBeyondTheRadiusCannotPeak)
{
  SpatialVolume volume;
  volume.grid.dims = Eigen::Vector3i(16, 16, 16);
  volume.grid.voxel_size = 1.0;
  volume.values.assign(volume.grid.size(), 0.0);
  volume.values[volume.grid.flatIndex(8, 0, 0)] = 5.0;   // lag -8 m on x: outside
  volume.values[volume.grid.flatIndex(15, 2, 1)] = 3.0;  // lag (-1, 2, 1): inside
  volume.values[volume.grid.flatIndex(1, 1, 15)] = -2.0; // the lowest value
  keepShiftsWithin(volume, Eigen::Vector3d::Zero(), 4.0);
  EXPECT_EQ(volume.values[volume.grid.flatIndex(8, 0, 0)], -2.0);
  EXPECT_EQ(volume.values[volume.grid.flatIndex(15, 2, 1)], 3.0);
  const SpatialCorrelationResult peak =
      findSpatialPeak(volume, SpatialPeakRefinement::kNone, 1, false);
  EXPECT_EQ(peak.index, Eigen::Vector3i(15, 2, 1));
}

TEST(AllowedPoses, AnAnswerOutsideTheRegionFallsBackInsideAndDoesNotConverge)
{
  AllowedPoses allowed;
  allowed.region = SearchRegion{Eigen::Vector3d(10.0, 0.0, 0.0), 5.0, 50.0};
  PhaserResult result;
  result.converged = result.diagnostics.verified = true;
  result.transformation.topRightCorner<3, 1>() = Eigen::Vector3d(30.0, 0.0, 0.0);
  Hypothesis outside, inside, better_outside;
  outside.transformation.topRightCorner<3, 1>() = Eigen::Vector3d(30.0, 0.0, 0.0);
  outside.verification.rank = 0.5;
  inside.transformation.topRightCorner<3, 1>() = Eigen::Vector3d(12.0, 1.0, 0.0);
  inside.verification.rank = 0.1;
  better_outside.transformation.topRightCorner<3, 1>() = Eigen::Vector3d(0.0, 0.0, 0.0);
  better_outside.verification.rank = 0.9;
  result.diagnostics.hypotheses = {outside, inside, better_outside};
  keepAllowed(result, allowed);
  EXPECT_FALSE(result.converged);
  EXPECT_FALSE(result.diagnostics.verified);
  EXPECT_EQ(result.chosen_hypothesis, 1);
  EXPECT_EQ(result.transformation, inside.transformation);
  EXPECT_EQ(result.diagnostics.verification.rank, 0.1);
  EXPECT_NE(result.diagnostics.refusal.find("20.00 m from the region's center"),
            std::string::npos)
      << result.diagnostics.refusal;

  result.diagnostics.hypotheses.clear(); // none inside: the nearest point of the region
  result.converged = true;
  result.transformation.topRightCorner<3, 1>() = Eigen::Vector3d(10.0, -20.0, 0.0);
  keepAllowed(result, allowed);
  EXPECT_FALSE(result.converged);
  const Eigen::Vector3d moved = result.transformation.topRightCorner<3, 1>();
  EXPECT_TRUE(moved.isApprox(Eigen::Vector3d(10.0, -5.0, 0.0)));

  result.converged = true; // inside: untouched
  result.diagnostics.refusal.clear();
  keepAllowed(result, allowed);
  EXPECT_TRUE(result.converged);
  EXPECT_TRUE(result.diagnostics.refusal.empty());
}

/** T with a rotation of \a deg about x after \a guess. */
Eigen::Matrix4d tilted(double deg, const Eigen::Matrix4d& guess)
{
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(deg * M_PI / 180.0, Eigen::Vector3d::UnitX())
          .toRotationMatrix();
  return T * guess;
}

TEST(AllowedPoses, TiltIsMeasuredAfterTheGuessAndClampedIntoTheCone)
{
  Eigen::Matrix4d guess = Eigen::Matrix4d::Identity();
  guess.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(1.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  PhaserParameters params;
  params.max_tilt_deg = 10.0;
  const AllowedPoses allowed =
      allowedPoses(params, Eigen::Matrix3Xd::Ones(3, 4), guess);
  EXPECT_TRUE(allowed.refusal(tilted(9.0, guess)).empty());
  EXPECT_TRUE(allowed.refusal(guess).empty()); // the guess's own tilt does not count
  EXPECT_NE(allowed.refusal(tilted(30.0, guess)).find("tilts 30.0 deg"),
            std::string::npos);
  PhaserResult result;
  result.converged = true;
  result.transformation = tilted(30.0, guess);
  keepAllowed(result, allowed); // no hypotheses: the tilt clamped to the cone
  EXPECT_FALSE(result.converged);
  const Eigen::Matrix3d R = result.transformation.topLeftCorner<3, 3>() *
                            guess.topLeftCorner<3, 3>().transpose();
  EXPECT_NEAR(std::acos(R(2, 2)) * 180.0 / M_PI, 10.0, 1e-9);
}

TEST(AllowedPoses, TheSearchAsksForItsShiftBoundRowsAndCandidates)
{
  PhaserParameters params;
  const Eigen::Matrix3Xd moved = Eigen::Matrix3Xd::Ones(3, 4);
  const AllowedPoses free = allowedPoses(params, moved, Eigen::Matrix4d::Identity());
  EXPECT_EQ(free.shiftBound(0.5), std::numeric_limits<double>::infinity());
  EXPECT_EQ(free.rotationRows(64), 0); // the whole grid
  EXPECT_EQ(free.orientationCandidates(10), 10);
  params.region = Region{1.0, 2.0, 0.0, 5.0, 50.0};
  params.max_tilt_deg = 10.0;
  const AllowedPoses narrow = allowedPoses(params, moved, Eigen::Matrix4d::Identity());
  EXPECT_EQ(narrow.shiftBound(0.5), 5.5); // the radius and one coarse voxel
  EXPECT_EQ(narrow.rotationRows(64), betaRowsForTilt(64, 10.0 * M_PI / 180.0));
  EXPECT_GT(narrow.rotationRows(64), 0);
  EXPECT_LT(narrow.rotationRows(64), 128);
  EXPECT_EQ(narrow.orientationCandidates(10), 2); // 20 % of them in a narrow cone
  EXPECT_EQ(narrow.orientationCandidates(0), 0);
  params.max_tilt_deg = 120.0; // the cone holds 75 % of the rotations
  EXPECT_EQ(allowedPoses(params, moved, Eigen::Matrix4d::Identity())
                .orientationCandidates(10),
            8);
}

} // namespace
} // namespace pcl::phaser::detail
