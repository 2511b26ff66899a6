/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * fitCovariance: the pose covariance from the point-to-plane fit of the samples.
 */
#include "point_test_support.h"
#include "uncertainty/pose_covariance.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace pcl::phaser {
namespace {

/** Points every \a step m on a floor (z = 0) and, when \a walls, on the walls x = 0
 *  and y = 0 of a 6 m corner, with their normals; \a noise m of Gaussian noise along
 *  the normal. */
void corner(double step, bool walls, double noise, unsigned seed,
            Eigen::Matrix3Xd& points, Eigen::Matrix3Xd& normals)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  std::vector<Eigen::Vector3d> p, n;
  const int cells = static_cast<int>(6.0 / step);
  for (int a = 1; a < cells; ++a)
    for (int b = 1; b < cells; ++b) {
      const double u = a * step, v = b * step;
      p.emplace_back(u, v, noise * n01(rng));
      n.emplace_back(0, 0, 1);
      if (!walls)
        continue;
      p.emplace_back(noise * n01(rng), u, v);
      n.emplace_back(1, 0, 0);
      p.emplace_back(u, noise * n01(rng), v);
      n.emplace_back(0, 1, 0);
    }
  points = test::toMatrix(p);
  normals = test::toMatrix(n);
}

struct Scene {
  PointIndex target;
  VerificationSamples samples;
};

Scene scene(bool walls, double target_noise, double sample_noise)
{
  Eigen::Matrix3Xd points, normals;
  corner(0.05, walls, target_noise, 1, points, normals);
  Scene s;
  s.target = PointIndex(points, 0.5, normals);
  corner(0.5, walls, sample_noise, 2, s.samples.points, s.samples.normals);
  s.samples.weights = Eigen::VectorXd::Ones(s.samples.points.cols());
  return s;
}

using Matrix6d = Eigen::Matrix<double, 6, 6>;

TEST(FitCovariance, SymmetricPositiveDefiniteAndGrowsWithTheResiduals)
{
  Matrix6d small, large;
  const Scene quiet = scene(true, 0.002, 0.01);
  const Scene noisy = scene(true, 0.002, 0.04);
  ASSERT_TRUE(fitCovariance(quiet.target, quiet.samples, {}, 2.0, small));
  ASSERT_TRUE(fitCovariance(noisy.target, noisy.samples, {}, 2.0, large));
  for (const Matrix6d* C : {&small, &large}) {
    EXPECT_TRUE(C->isApprox(C->transpose()));
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix6d>(*C).eigenvalues()[0], 0.0);
  }
  // Four times the residuals: about sixteen times the variances.
  for (int k = 0; k < 6; ++k)
    EXPECT_GT(large(k, k), 4.0 * small(k, k)) << k;
}

TEST(FitCovariance, CoversTheStepToTheOptimum)
{
  const Scene s = scene(true, 0.0, 0.0);
  RigidPose off;
  off.t = Eigen::Vector3d(0.05, -0.03, 0.02); // the samples moved 5 cm off the corner
  Matrix6d C;
  ASSERT_TRUE(fitCovariance(s.target, s.samples, off, 2.0, C));
  // The error of this pose (the optimum is the identity): nu = -t, omega = 0.
  Eigen::Matrix<double, 6, 1> e;
  e << 0, 0, 0, -off.t;
  EXPECT_LE(e.dot(C.ldlt().solve(e)), 1.0 + 1e-6);
}

TEST(FitCovariance, RefusesUnmeasuredDirectionsAndFewSamples)
{
  Matrix6d C = Matrix6d::Identity();
  const Scene floor = scene(false, 0.002, 0.01); // x, y and the yaw are free
  EXPECT_FALSE(fitCovariance(floor.target, floor.samples, {}, 2.0, C));
  Scene few = scene(true, 0.002, 0.01);
  few.samples.points.conservativeResize(3, kMinFitSamples - 1);
  few.samples.normals.conservativeResize(3, kMinFitSamples - 1);
  few.samples.weights.conservativeResize(kMinFitSamples - 1);
  EXPECT_FALSE(fitCovariance(few.target, few.samples, {}, 2.0, C));
  EXPECT_TRUE(C.isIdentity()); // untouched
  EXPECT_FALSE(fitCovariance(few.target, few.samples, {}, 0.0, C));
}

} // namespace
} // namespace pcl::phaser
