/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The gravity prior (PhaserParameters::max_tilt_deg) on real scans from ../shared/data
 * (skipped with a message when absent): under random poses tilted less than the prior,
 * it finds as many as the full search.
 */
#include "protocol.h"
#include "real_data_support.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>
#include <pcl/point_types.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace {

using PointT = pcl::PointXYZI;
using Cloud = pcl::PointCloud<PointT>;
constexpr double kDeg = M_PI / 180.0;

/** Whether \a scan seen from \a T (the source is T^-1 scan) is registered within
 *  2 deg / 0.3 m and converged, with the prior \a max_tilt_deg (0: off); the tilt
 *  of the result (deg) into \a tilt. */
bool found(const Cloud::Ptr& scan, const Eigen::Matrix4d& T, double max_tilt_deg,
           double& tilt)
{
  auto source = pcl::make_shared<Cloud>();
  pcl::transformPointCloud(*scan, *source, Eigen::Matrix4d(T.inverse()));
  pcl::PhaserRegistration<PointT, PointT> phaser;
  pcl::phaser::PhaserParameters params = phaser.getParameters();
  params.num_threads = 2;
  params.max_tilt_deg = max_tilt_deg;
  phaser.setParameters(params);
  phaser.setInputSource(source);
  phaser.setInputTarget(scan);
  Cloud aligned;
  phaser.align(aligned);
  const Eigen::Matrix4d G = phaser.getFinalTransformation().cast<double>();
  tilt = std::acos(std::min(1.0, G(2, 2))) / kDeg;
  return phaser.hasConverged() && pcl::phaser::bench::rreDeg(G, T) < 2.0 &&
         pcl::phaser::bench::rteM(G, T) < 0.3;
}

/** \a poses random poses of \a relative tilted under 8 deg (uniform yaw, up to 2 m):
 *  as many found with max_tilt_deg = 10 as without the prior, and every result of the
 *  prior within it. */
void sameSuccess(const std::string& relative, int poses, unsigned seed)
{
  PCL_PHASER_REQUIRE_DATA(relative);
  const Cloud::Ptr scan = pcl::phaser::test::loadFiniteCloud<PointT>(relative);
  ASSERT_GT(scan->size(), 1000u);
  std::mt19937 rng(seed);
  int full_ok = 0, prior_ok = 0;
  for (int k = 0; k < poses; ++k) {
    const Eigen::Matrix4d T = pcl::phaser::bench::randomPose(rng, 2.0, 8.0 * kDeg);
    double full_tilt = 0.0, prior_tilt = 0.0;
    const bool full = found(scan, T, 0.0, full_tilt);
    const bool prior = found(scan, T, 10.0, prior_tilt);
    full_ok += full;
    prior_ok += prior;
    std::printf("  pose %d (tilt %.1f deg): full %s, prior %s (tilt %.1f deg)\n", k,
                std::acos(T(2, 2)) / kDeg, full ? "found" : "missed",
                prior ? "found" : "missed", prior_tilt);
    EXPECT_LE(prior_tilt, 10.0 + 90.0 / 64.0) << "pose " << k;
  }
  EXPECT_EQ(prior_ok, full_ok) << relative;
  EXPECT_GE(prior_ok, poses - 1) << relative;
}

TEST(TiltPrior, SameSuccessOnRestrictedPoses)
{
  sameSuccess("lidar/kitti_raw_hdl64/0000000000.bin", 8, 11);
  sameSuccess("lidar/hdl32_fastgicp/251370668.pcd", 8, 12);
}

} // namespace
