/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The cues of ProjectionCenter::Automatic on synthetic direction sets with known
 * answers.
 */
#include "pipeline/projection_center.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

using pcl::phaser::looksSensorCentered;
using pcl::phaser::polarFraction;
using pcl::phaser::viewCoverage;

/** \a n points at ranges 2..30 m in directions uniform over the band |elevation| <=
 *  \a half_fov, seen from \a center and rotated by \a R. */
Eigen::Matrix3Xd band(int n, double half_fov, const Eigen::Matrix3d& R,
                      const Eigen::Vector3d& center, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::Matrix3Xd p(3, n);
  for (int i = 0; i < n; ++i) {
    const double z = std::sin(half_fov) * (2.0 * u(rng) - 1.0); // uniform in area
    const double phi = 2.0 * M_PI * u(rng), rho = std::sqrt(1.0 - z * z);
    const double range = 2.0 + 28.0 * u(rng);
    p.col(i) = center + R * (range * Eigen::Vector3d(rho * std::cos(phi),
                                                     rho * std::sin(phi), z));
  }
  return p;
}

const Eigen::Vector3d kOrigin = Eigen::Vector3d::Zero();

} // namespace

TEST(ProjectionCenter, CoverageOfKnownRegions)
{
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  // The whole sphere, the band |elevation| <= 30 deg (area 1/2) and <= 15 deg (0.26):
  // cells on the band's edge count whole, so the estimate exceeds the area by at most
  // one ring of cells on each side (~0.1 of the sphere at 11 deg cells).
  // The polar cells are so small that they hold fewer than the thousandth of the
  // points a cell needs: the whole sphere reads 1 minus the two polar rings (0.019).
  const double whole = viewCoverage(band(200000, M_PI / 2, I, kOrigin, 1), kOrigin);
  EXPECT_GE(whole, 0.98);
  EXPECT_LE(whole, 1.0);
  const double c30 = viewCoverage(band(200000, M_PI / 6, I, kOrigin, 2), kOrigin);
  EXPECT_GE(c30, 0.5);
  EXPECT_LE(c30, 0.62);
  const double c15 = viewCoverage(band(200000, M_PI / 12, I, kOrigin, 3), kOrigin);
  EXPECT_GE(c15, std::sin(M_PI / 12));
  EXPECT_LE(c15, std::sin(M_PI / 12) + 0.15);
  // The same band seen from 1 km away is a speck (one or two cells, ~0.012 each).
  EXPECT_LT(
      viewCoverage(band(20000, M_PI / 12, I, Eigen::Vector3d(1000, 0, 0), 4), kOrigin),
      0.03);
  // Nothing to see: empty, or everything at the viewpoint.
  EXPECT_EQ(viewCoverage(Eigen::Matrix3Xd(3, 0), kOrigin), 0.0);
  EXPECT_EQ(viewCoverage(Eigen::Matrix3Xd::Zero(3, 10), kOrigin), 0.0);
  EXPECT_EQ(polarFraction(Eigen::Matrix3Xd::Zero(3, 10), kOrigin), 0.0);
}

TEST(ProjectionCenter, PolarFractionIsRotationInvariant)
{
  // A LiDAR band (+-20 deg) under any rotation: nothing near its poles. The whole
  // sphere: 1 - cos(45 deg) ~ 0.29 of uniform directions lie within 45 deg of a pole.
  std::mt19937 rng(5);
  for (int k = 0; k < 5; ++k) {
    const Eigen::Matrix3d R =
        Eigen::Quaterniond(Eigen::Vector4d::NullaryExpr([&](Eigen::Index) {
                             return std::normal_distribution<double>()(rng);
                           }).normalized())
            .toRotationMatrix();
    const Eigen::Vector3d center(3.0 * k, -1.0, 0.5 * k);
    const Eigen::Matrix3Xd lidar = band(50000, 20 * M_PI / 180, R, center, 10 + k);
    EXPECT_EQ(polarFraction(lidar, center), 0.0) << k;
    EXPECT_TRUE(looksSensorCentered(lidar, center)) << k;
    // Seen from 40 m beside its sensor it is no longer centered on the viewpoint.
    EXPECT_FALSE(looksSensorCentered(lidar, center + R * Eigen::Vector3d(40, 0, 0)))
        << k;
    const Eigen::Matrix3Xd sphere = band(50000, M_PI / 2, R, center, 20 + k);
    EXPECT_NEAR(polarFraction(sphere, center), 1.0 - std::sqrt(0.5), 0.03) << k;
    EXPECT_FALSE(looksSensorCentered(sphere, center)) << k;
  }
}

// A scan's sensor origin lies on its data, also for a narrow sector of it and for a
// small object about its origin; the origin of the same scan moved 200 m away (a map in
// a site frame) or of an object 30 m off does not; no finite point: false.
TEST(ProjectionCenter, OriginOnData)
{
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3Xd scan = band(20000, 0.4, I, kOrigin, 11);
  EXPECT_TRUE(pcl::phaser::originOnData(scan, kOrigin));
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < scan.cols(); ++i)
    if (std::abs(std::atan2(scan(1, i), scan(0, i))) < 0.1 * M_PI) // a 10 % sector
      kept.push_back(i);
  EXPECT_TRUE(pcl::phaser::originOnData(scan(Eigen::all, kept), kOrigin));
  const Eigen::Vector3d far(160.0, -120.0, 5.0);
  EXPECT_FALSE(pcl::phaser::originOnData(scan.colwise() + far, kOrigin));
  EXPECT_TRUE(pcl::phaser::originOnData(scan.colwise() + far, far));
  const Eigen::Matrix3Xd object = 0.1 * Eigen::Matrix3Xd::Random(3, 500); // 20 cm
  EXPECT_TRUE(pcl::phaser::originOnData(object, kOrigin));
  EXPECT_FALSE(
      pcl::phaser::originOnData(object.colwise() + Eigen::Vector3d(30, 0, 0), kOrigin));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(
      pcl::phaser::originOnData(Eigen::Matrix3Xd::Constant(3, 4, nan), kOrigin));
  EXPECT_FALSE(pcl::phaser::originOnData(Eigen::Matrix3Xd(3, 0), kOrigin));
}
