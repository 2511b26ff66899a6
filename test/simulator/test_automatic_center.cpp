/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * ProjectionCenter::Automatic on simulated LiDAR scans: the choice, the target cache
 * across choices, and bad input.
 */
#include "scan_simulator.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

namespace {

using PointT = pcl::PointXYZI;
using Cloud = pcl::PointCloud<PointT>;
using Phaser = pcl::PhaserRegistration<PointT, PointT>;
using Center = Phaser::ProjectionCenter;

double rreDeg(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B)
{
  const Eigen::Matrix3d d =
      A.topLeftCorner<3, 3>() * B.topLeftCorner<3, 3>().transpose();
  return std::acos(std::clamp((d.trace() - 1.0) / 2.0, -1.0, 1.0)) * 180.0 / M_PI;
}

} // namespace

TEST(AutomaticCenter, SimulatedScanPairUsesTheSensorOriginAndTheCache)
{
  const pcl::phaser::ScanPair pair = pcl::phaser::makeDemoPair(2);
  const auto source = pcl::make_shared<Cloud>(pair.source);
  const auto target = pcl::make_shared<Cloud>(pair.target);
  Phaser phaser;
  phaser.setNumberOfThreads(2);
  phaser.setProjectionCenter(Center::Automatic);
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  Cloud out;
  phaser.align(out);
  ASSERT_TRUE(phaser.hasConverged());
  EXPECT_EQ(phaser.getResult().projection_center, Center::SensorOrigin);
  EXPECT_LT(
      rreDeg(phaser.getFinalTransformation().cast<double>(), pair.T_target_source),
      2.0);
  const Eigen::Matrix4f first = phaser.getFinalTransformation();
  phaser.align(out); // same choice: the cached target model is reused
  EXPECT_EQ(phaser.getResult().diagnostics.times.target, 0.0);
  EXPECT_EQ(phaser.getFinalTransformation(), first);

  // The target scan itself, yawed by 90 deg and moved 1 km from its origin (several
  // times its extent): no longer seen from its origin, so both clouds are projected
  // about their centroids (the same points: the centroids correspond) and the target
  // is prepared again.
  Eigen::Matrix4d away = Eigen::Matrix4d::Identity();
  away.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
  away(0, 3) = 1000.0;
  const auto far = pcl::make_shared<Cloud>();
  pcl::transformPointCloud(*target, *far, away);
  phaser.setInputSource(far);
  phaser.align(out);
  ASSERT_TRUE(phaser.hasConverged());
  EXPECT_EQ(phaser.getResult().projection_center, Center::Centroid);
  EXPECT_GT(phaser.getResult().diagnostics.times.target, 0.0);
  const Eigen::Matrix4d truth = away.inverse();
  const Eigen::Matrix4d estimate = phaser.getFinalTransformation().cast<double>();
  EXPECT_LT(rreDeg(estimate, truth), 2.0);
  // The translation carries the 1 km lever arm of any rotation error: judge where the
  // points land instead (mean displacement against the truth).
  double displacement = 0.0;
  for (const PointT& p : *far) {
    const Eigen::Vector4d q(p.x, p.y, p.z, 1.0);
    displacement += ((estimate - truth) * q).norm();
  }
  EXPECT_LT(displacement / static_cast<double>(far->size()), 0.1);
}

TEST(AutomaticCenter, BadInputFailsCleanly)
{
  // Empty, a single point at the center, all NaN: as the source and as the target, on
  // fresh objects (PCL's setInputSource/Target refuse an empty cloud and keep the old
  // one, so each case starts clean).
  const pcl::phaser::ScanPair pair = pcl::phaser::makeDemoPair(1);
  const auto good = pcl::make_shared<Cloud>(pair.target);
  for (const Cloud::Ptr& bad :
       {pcl::make_shared<Cloud>(), pcl::make_shared<Cloud>(1, 1, PointT(0, 0, 0, 1)),
        pcl::make_shared<Cloud>(50, 1, PointT(NAN, 0, 0, 1))}) {
    for (int as_target = 0; as_target < 2; ++as_target) {
      Phaser phaser;
      phaser.setProjectionCenter(Center::Automatic);
      phaser.setInputSource(as_target ? good : bad);
      phaser.setInputTarget(as_target ? bad : good);
      Cloud out;
      phaser.align(out);
      EXPECT_FALSE(phaser.hasConverged()) << bad->size() << " " << as_target;
      EXPECT_EQ(phaser.getFinalTransformation(), Eigen::Matrix4f::Identity());
    }
  }
}
