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

// A LiDAR band under any rotation is seen from its sensor (its nearest return 2 m off,
// its extent 60 m); seen from 100 m beside it (nearest 70 m), or the same band shrunk
// to an object 0.6 m across held 1 m away, it is not; nothing finite or nothing at
// all: false.
TEST(ProjectionCenter, SeenFromTheSensorAnyRotation)
{
  std::mt19937 rng(5);
  for (int k = 0; k < 5; ++k) {
    const Eigen::Matrix3d R =
        Eigen::Quaterniond(Eigen::Vector4d::NullaryExpr([&](Eigen::Index) {
                             return std::normal_distribution<double>()(rng);
                           }).normalized())
            .toRotationMatrix();
    const Eigen::Vector3d center(3.0 * k, -1.0, 0.5 * k);
    const Eigen::Matrix3Xd lidar = band(50000, 20 * M_PI / 180, R, center, 10 + k);
    EXPECT_TRUE(looksSensorCentered(lidar, center)) << k;
    EXPECT_FALSE(looksSensorCentered(lidar, center + R * Eigen::Vector3d(100, 0, 0)))
        << k;
    Eigen::Matrix3Xd object = (lidar.colwise() - center) * 0.01;
    object.colwise() += center + R * Eigen::Vector3d(1, 0, 0);
    EXPECT_FALSE(looksSensorCentered(object, center)) << k;
  }
  EXPECT_FALSE(looksSensorCentered(Eigen::Matrix3Xd(3, 0), kOrigin));
  EXPECT_FALSE(looksSensorCentered(
      Eigen::Matrix3Xd::Constant(3, 4, std::numeric_limits<double>::quiet_NaN()),
      kOrigin));
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

namespace {

/** \a n points on a room-sized sphere of radius 5 m about \a center with bumps: one
 *  surface per direction, as a scanner at \a center sees it. */
Eigen::Matrix3Xd roomSeenFrom(const Eigen::Vector3d& center, int n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Matrix3Xd p(3, n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d d = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    p.col(i) = center + (5.0 + 0.3 * std::sin(4.0 * d.x()) * std::cos(3.0 * d.z())) * d;
  }
  return p;
}

} // namespace

TEST(HiddenShare, AScanSeesNothingBehindItsSurface)
{
  const Eigen::Vector3d center(1.0, -2.0, 0.5);
  EXPECT_LT(pcl::phaser::hiddenShare(roomSeenFrom(center, 40000, 1), center), 0.01);
}

TEST(HiddenShare, TwoShellsAboutAPointAreNotSeenFromIt)
{
  // Two caps (within 30 deg of +z) at 5 and 10 m: from the center the outer one lies
  // behind the inner one (an object's frame origin inside it, not a sensor). About 1.1
  // points of each per direction cell: a third of the outer ones share a cell.
  const Eigen::Vector3d center = Eigen::Vector3d::Zero();
  const auto cap = [&](double range, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Eigen::Matrix3Xd p(3, 20000);
    for (Eigen::Index i = 0; i < p.cols(); ++i) {
      const double z = 1.0 - u(rng) * (1.0 - std::cos(M_PI / 6.0)),
                   a = 2 * M_PI * u(rng);
      const double r = std::sqrt(1.0 - z * z);
      p.col(i) = range * Eigen::Vector3d(r * std::cos(a), r * std::sin(a), z);
    }
    return p;
  };
  Eigen::Matrix3Xd caps(3, 40000);
  caps << cap(5.0, 2), cap(10.0, 3);
  EXPECT_LT(pcl::phaser::hiddenShare(caps.leftCols(20000), center), 0.01);
  const double share = pcl::phaser::hiddenShare(caps, center);
  EXPECT_GT(share, 2.0 * pcl::phaser::kMaxHiddenShare);
  EXPECT_LT(share, 0.5);
  EXPECT_EQ(pcl::phaser::hiddenShare(Eigen::Matrix3Xd(3, 0), center), 0.0);
}
