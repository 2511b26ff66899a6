/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * refinePose: Gauss-Newton on the point-to-plane distances that the verification
 * score rewards, from a pose near the truth; its trust region; too few matches.
 */
#include "point_test_support.h"
#include "verification/pose_refinement.h"
#include "index/point_index.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace pcl::phaser;

namespace {

constexpr double kDeg = M_PI / 180.0;

/** A room corner with a box: floor z = 0, walls x = 4 and y = 3, and a box face
 *  x = 1 (|y| < 1, 0 < z < 1), sampled every \a h meters, with unit normals. */
void corner(double h, Eigen::Matrix3Xd& points, Eigen::Matrix3Xd& normals)
{
  std::vector<Eigen::Vector3d> p, n;
  for (double a = -4.0; a <= 4.0; a += h)
    for (double b = -3.0; b <= 3.0; b += h) {
      p.emplace_back(a, b, 0.0);
      n.emplace_back(0.0, 0.0, 1.0);
    }
  for (double a = -3.0; a <= 3.0; a += h)
    for (double z = 0.0; z <= 2.5; z += h) {
      p.emplace_back(4.0, a, z);
      n.emplace_back(-1.0, 0.0, 0.0);
    }
  for (double a = -4.0; a <= 4.0; a += h)
    for (double z = 0.0; z <= 2.5; z += h) {
      p.emplace_back(a, 3.0, z);
      n.emplace_back(0.0, -1.0, 0.0);
    }
  for (double a = -1.0; a <= 1.0; a += h)
    for (double z = 0.0; z <= 1.0; z += h) {
      p.emplace_back(1.0, a, z);
      n.emplace_back(-1.0, 0.0, 0.0);
    }
  points = test::toMatrix(p);
  normals = test::toMatrix(n);
}

struct Scene {
  PointIndex target;
  VerificationSamples samples;
  RigidPose truth; ///< maps the samples onto the target
};

/** Target = the corner; samples = the corner moved by truth^-1 (so truth maps them
 *  back), every fourth point. */
Scene makeScene()
{
  Eigen::Matrix3Xd points, normals;
  corner(0.05, points, normals);
  Scene s;
  s.target = PointIndex(points, 0.3, normals);
  s.truth.R = (Eigen::AngleAxisd(25 * kDeg, Eigen::Vector3d::UnitZ()) *
               Eigen::AngleAxisd(3 * kDeg, Eigen::Vector3d::UnitX()))
                  .toRotationMatrix();
  s.truth.t = Eigen::Vector3d(0.7, -0.4, 0.1);
  const Eigen::Index m = points.cols() / 4;
  s.samples.points.resize(3, m);
  s.samples.normals.resize(3, m);
  s.samples.weights = Eigen::VectorXd::Ones(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    s.samples.points.col(i) = s.truth.R.transpose() * (points.col(4 * i) - s.truth.t);
    s.samples.normals.col(i) = s.truth.R.transpose() * normals.col(4 * i);
  }
  return s;
}

/** \a truth turned by 2 deg about (1, 2, 3) and moved by \a shift. */
RigidPose offset(const RigidPose& truth, const Eigen::Vector3d& shift)
{
  RigidPose pose;
  pose.R = Eigen::AngleAxisd(2 * kDeg, Eigen::Vector3d(1, 2, 3).normalized()) * truth.R;
  pose.t = truth.t + shift;
  return pose;
}

double angleBetween(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B)
{
  return std::abs(Eigen::AngleAxisd(A * B.transpose()).angle());
}

} // namespace

TEST(PoseRefinement, ConvergesFromANearbyPose)
{
  const Scene s = makeScene();
  const RigidPose start = offset(s.truth, Eigen::Vector3d(0.1, -0.08, 0.05));
  const RigidPose refined = refinePose(s.target, s.samples, start, 10);
  EXPECT_LT(angleBetween(refined.R, s.truth.R), 0.05 * kDeg);
  EXPECT_LT((refined.t - s.truth.t).norm(), 0.005);
  // Zero iterations: the start.
  const RigidPose same = refinePose(s.target, s.samples, start, 0);
  EXPECT_TRUE(same.R.isApprox(start.R) && same.t.isApprox(start.t));
}

TEST(PoseRefinement, TrustRegionReturnsTheStart)
{
  const Scene s = makeScene();
  RigidPose start = s.truth;
  start.t += Eigen::Vector3d(0.15, 0.0, 0.0);
  // The refinement must move 0.15 m: a 5 cm trust region refuses it.
  const RigidPose kept = refinePoseWithin(s.target, s.samples, start, 10, 1.0, 0.05);
  EXPECT_TRUE(kept.t.isApprox(start.t));
  const RigidPose moved = refinePoseWithin(s.target, s.samples, start, 10, 1.0, 0.5);
  EXPECT_LT((moved.t - s.truth.t).norm(), 0.005);
}

TEST(PoseRefinement, TooFewMatchesKeepTheStart)
{
  const Scene s = makeScene();
  VerificationSamples few;
  few.points = s.samples.points.leftCols(5);
  few.normals = s.samples.normals.leftCols(5);
  few.weights = Eigen::VectorXd::Ones(5);
  RigidPose start = s.truth;
  start.t.x() += 0.1;
  const RigidPose kept = refinePose(s.target, few, start, 10);
  EXPECT_TRUE(kept.t.isApprox(start.t));
  // Far from the target (no sample within the radius): nothing to climb.
  start.t.x() += 50.0;
  EXPECT_TRUE(refinePose(s.target, s.samples, start, 10).t.isApprox(start.t));
}

TEST(PoseRefinement, FirstStepAgainstAWiderIndexReachesAFarStart)
{
  // A start 0.6 m off across both walls (twice the radius 0.3): only the floor's
  // samples have a target point within the radius, so the steps pin height, roll and
  // pitch and leave the walls apart. One step against the same target indexed at
  // 0.8 m reaches the walls and starts the climb in the truth's basin.
  const Scene s = makeScene();
  const RigidPose start = offset(s.truth, Eigen::Vector3d(0.45, -0.4, 0.0));
  Eigen::Matrix3Xd points, normals;
  corner(0.05, points, normals);
  const PointIndex reach(points, 0.8, normals);
  const RigidPose near =
      refinePoseWithin(s.target, s.samples, start, 10, 10 * kDeg, 2.0);
  EXPECT_GT((near.t - s.truth.t).norm(), 0.3);
  const RigidPose reached =
      refinePoseWithin(s.target, s.samples, start, 10, 10 * kDeg, 2.0, &reach);
  EXPECT_LT(angleBetween(reached.R, s.truth.R), 0.05 * kDeg);
  EXPECT_LT((reached.t - s.truth.t).norm(), 0.005);
}
