/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Real scans from ../shared/data (skipped with a message when absent):
 *  - a scan seen again from 20 random poses (uniform rotation, translation up to 2 m),
 *    recovered by the global stage alone, then by ICP started from it;
 *  - real pairs against their reference poses.
 */
#include "../registration/test_data.h"

#include <pcl_phaser/cloud_io.h>
#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>
#include <pcl/filters/filter.h>
#include <pcl/point_types.h>
#include <pcl/registration/icp.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace {

using PointT = pcl::PointXYZI;
using Cloud = pcl::PointCloud<PointT>;
constexpr double kDeg = M_PI / 180.0;

Cloud::Ptr load(const std::string& relative)
{
  auto cloud = pcl::make_shared<Cloud>();
  std::string error;
  if (!pcl::phaser::loadCloud(pcl_phaser::test::dataPath(relative), *cloud, &error))
    ADD_FAILURE() << error;
  pcl::Indices kept;
  pcl::removeNaNFromPointCloud(*cloud, *cloud, kept);
  return cloud;
}

double rreDeg(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B)
{
  return Eigen::AngleAxisd(Eigen::Matrix3d(A.topLeftCorner<3, 3>().transpose() *
                                           B.topLeftCorner<3, 3>()))
             .angle() /
         kDeg;
}

double rte(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B)
{
  return (A.topRightCorner<3, 1>() - B.topRightCorner<3, 1>()).norm();
}

/** Uniform random rotation, translation uniform in the ball of radius \a t_max. */
Eigen::Matrix4d randomPose(std::mt19937& rng, double t_max)
{
  std::normal_distribution<double> n01;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::Quaterniond(n01(rng), n01(rng), n01(rng), n01(rng))
                                .normalized()
                                .toRotationMatrix();
  const Eigen::Vector3d dir =
      Eigen::Vector3d(n01(rng), n01(rng), n01(rng)).normalized();
  T.topRightCorner<3, 1>() = dir * t_max * std::cbrt(u(rng));
  return T;
}

/** The 20-pose protocol of the end-to-end issue. */
void runRandomPoses(const std::string& relative, int poses, unsigned seed)
{
  PCL_PHASER_REQUIRE_DATA(relative);
  const Cloud::Ptr scan = load(relative);
  ASSERT_GT(scan->size(), 1000u);
  std::mt19937 rng(seed);
  int global_ok = 0;
  for (int k = 0; k < poses; ++k) {
    const Eigen::Matrix4d T = randomPose(rng, 2.0);
    auto source = pcl::make_shared<Cloud>();
    pcl::transformPointCloud(*scan, *source, Eigen::Matrix4d(T.inverse()));
    pcl::PhaserRegistration<PointT, PointT> phaser;
    phaser.setNumberOfThreads(2);
    phaser.setInputSource(source);
    phaser.setInputTarget(scan);
    Cloud aligned;
    phaser.align(aligned);
    const Eigen::Matrix4d G = phaser.getFinalTransformation().cast<double>();
    const double r = rreDeg(G, T), t = rte(G, T);
    const bool ok = phaser.hasConverged() && r < 2.0 && t < 0.3;
    global_ok += ok;
    std::printf("  pose %2d: global RRE %7.3f deg RTE %6.3f m %s", k, r, t,
                ok ? "" : "(miss)");
    if (ok) {
      pcl::IterativeClosestPoint<PointT, PointT> icp;
      icp.setInputSource(source);
      icp.setInputTarget(scan);
      icp.setMaxCorrespondenceDistance(1.0);
      icp.setMaximumIterations(50);
      icp.setTransformationEpsilon(1e-10);
      icp.align(aligned, phaser.getFinalTransformation());
      const Eigen::Matrix4d I = icp.getFinalTransformation().cast<double>();
      std::printf(" | ICP RRE %.4f deg RTE %.4f m", rreDeg(I, T), rte(I, T));
      EXPECT_LT(rreDeg(I, T), 0.2) << "pose " << k;
      EXPECT_LT(rte(I, T), 0.05) << "pose " << k;
    }
    std::printf("\n");
  }
  EXPECT_GE(global_ok, poses - poses / 20) << relative;
}

} // namespace

TEST(RealScans, Hdl32RandomPoses)
{
  runRandomPoses("lidar/hdl32_fastgicp/251370668.pcd", 20, 1);
}

TEST(RealScans, KittiRandomPoses)
{
  runRandomPoses("lidar/kitti_raw_hdl64/0000000000.bin", 20, 2);
}

TEST(RealScans, KittiSyntheticRandomPoses)
{
  runRandomPoses("lidar/kitti_synthetic_gt/cloud049.ply", 20, 3);
}
