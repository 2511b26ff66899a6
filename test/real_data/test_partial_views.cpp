/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Partial views: the source is an azimuth wedge of a real scan (what a sensor with a
 * narrower horizontal field of view sees) under a random large pose. The re-projection
 * passes must refine the chosen hypothesis rather than jump to another peak of the
 * wedge's correlation.
 */
#include "protocol.h"
#include "real_data_support.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>
#include <pcl/point_types.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace {

using pcl::phaser::bench::Cloud;
using pcl::phaser::bench::PointT;

/** Registers \a source onto \a target with defaults (2 threads) and expects \a truth
 *  within 5 deg and \a max_rte meters, converged. */
void expectRegistered(const Cloud::Ptr& source, const Cloud::ConstPtr& target,
                      const Eigen::Matrix4d& truth, double max_rte,
                      const std::string& what)
{
  pcl::PhaserRegistration<PointT, PointT> phaser;
  phaser.setNumberOfThreads(2);
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  Cloud aligned;
  phaser.align(aligned);
  const Eigen::Matrix4d estimate = phaser.getFinalTransformation().cast<double>();
  EXPECT_LT(pcl::phaser::bench::rreDeg(estimate, truth), 5.0) << what;
  EXPECT_LT(pcl::phaser::bench::rteM(estimate, truth), max_rte) << what;
  EXPECT_TRUE(phaser.hasConverged()) << what;
}

} // namespace

// A quarter of the HDL-32 scan (90 deg of azimuth), ten random poses (seed 7, drawn
// before any change was tried on them): every one within 5 deg and 0.3 m, converged.
TEST(PartialViews, QuarterWedgeRegistersAndConverges)
{
  const std::string file = "lidar/hdl32_fastgicp/251370668.pcd";
  PCL_PHASER_REQUIRE_DATA(file);
  const auto scan = pcl::phaser::test::loadFiniteCloud<PointT>(file);
  pcl::phaser::bench::Condition wedge;
  ASSERT_TRUE(pcl::phaser::bench::parseCondition("overlap:0.25", wedge));
  std::mt19937 rng(7);
  for (int trial = 0; trial < 10; ++trial) {
    auto source = pcl::make_shared<Cloud>(*scan);
    pcl::phaser::bench::applyCondition(wedge, *source, rng);
    const Eigen::Matrix4d T = pcl::phaser::bench::randomPose(rng, 2.0);
    pcl::transformPointCloud(*source, *source, T.cast<float>());
    expectRegistered(source, scan, T.inverse(), 0.3, "trial " + std::to_string(trial));
  }
}

// A 36 deg wedge of the KITTI scan (centered at 40.67 deg azimuth) under a pure
// rotation: pose 2 of `--conditions overlap:0.1 --t-max 0`). Pass 1's
// best pose meets every limit but a distinct hypothesis ranks about as high; the
// further translation peaks of every rotation then hold the right pose, which wins and
// converges. With them tried only when nothing meets the limits, this ended at
// 88 deg / 10 m, refused.
TEST(PartialViews, TenthWedgeWhosePassOneWinnerDoesNotStandOutIsRescued)
{
  const std::string file = "lidar/kitti_raw_hdl64/0000000000.bin";
  PCL_PHASER_REQUIRE_DATA(file);
  const auto scan = pcl::phaser::test::loadFiniteCloud<PointT>(file);
  auto source = pcl::make_shared<Cloud>(*scan);
  pcl::phaser::bench::keepSector(*source, 40.671649 * M_PI / 180.0, 0.1 * M_PI);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity(); // target -> source
  T.topLeftCorner<3, 3>() =
      Eigen::Quaterniond(0.237153389, 0.639019600, -0.473565166, 0.557806646)
          .normalized()
          .toRotationMatrix()
          .transpose();
  pcl::transformPointCloud(*source, *source, T.cast<float>());
  expectRegistered(source, scan, T.inverse(), 0.6, "KITTI wedge");
}
