/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Relocalization in a prior map: a map aggregated from every other balm_handheld scan
 * (0, 12, 24, ..., thinned to 0.1 m voxel centroids) and query scans that are not in
 * it, with default parameters. The map is kept in scan 0's frame and moved rigidly into
 * site frames whose origin lies 200 m and 5 km from the data (35 deg of yaw): the
 * queries register in all three. Success is judged at 5 deg / 0.6 m (the reference
 * poses are LiDAR-inertial odometry, good to centimeters).
 */
#include "prior_map.h"
#include "real_data_support.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>

#include <Eigen/Geometry>

#include <cmath>
#include <string>

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZI>;
const std::string kDir = "lidar/balm_handheld";

/** The map of every other scan moved \a distance meters away (bench/prior_map.h). */
pcl::phaser::bench::PriorMap priorMap(double distance)
{
  pcl::phaser::bench::PriorMap map;
  std::string error;
  if (!pcl::phaser::bench::buildPriorMap(pcl::phaser::test::dataPath(kDir), 2, 0.1,
                                         pcl::phaser::bench::siteFrame(distance), map,
                                         error))
    ADD_FAILURE() << error;
  return map;
}

/** Every \a every -th query (from the first) against the map moved \a distance away:
 *  each within 5 deg / 0.6 m of site T_world_query, and converged, with defaults. */
void expectQueriesRegister(double distance, int every)
{
  PCL_PHASER_REQUIRE_DATA(kDir + "/poses_T_world_lidar.txt");
  const pcl::phaser::bench::PriorMap map = priorMap(distance);
  ASSERT_TRUE(map.cloud && !map.cloud->empty());
  pcl::PhaserRegistration<pcl::PointXYZI, pcl::PointXYZI> phaser;
  phaser.setNumberOfThreads(2);
  phaser.setInputTarget(map.cloud);
  for (std::size_t k = 0; k < map.queries.size();
       k += static_cast<std::size_t>(every)) {
    const int index = map.queries[k];
    phaser.setInputSource(pcl::phaser::test::loadFiniteCloud<pcl::PointXYZI>(
        kDir + "/full" + std::to_string(index) + ".pcd"));
    Cloud aligned;
    phaser.align(aligned);
    const Eigen::Matrix4d truth = map.site * map.world_lidar.at(index);
    const Eigen::Matrix4d estimate = phaser.getFinalTransformation().cast<double>();
    const Eigen::Matrix3d dR =
        estimate.topLeftCorner<3, 3>().transpose() * truth.topLeftCorner<3, 3>();
    const std::string which = "query full" + std::to_string(index) + ".pcd, map " +
                              std::to_string(distance) + " m away";
    EXPECT_LT(Eigen::AngleAxisd(dR).angle() * 180.0 / M_PI, 5.0) << which;
    EXPECT_LT((estimate.topRightCorner<3, 1>() - truth.topRightCorner<3, 1>()).norm(),
              0.6)
        << which;
    EXPECT_TRUE(phaser.hasConverged()) << which;
  }
}

// Every third query (5 of 15) in scan 0's frame and 5 km away; all 15 at 200 m
// (pcl_phaser_bench prior-map runs all 15 in every frame).
TEST(PriorMap, QueriesNotInTheMapRegister)
{
  expectQueriesRegister(0.0, 3);
}

TEST(PriorMap, SiteFrame200MetersAway)
{
  expectQueriesRegister(200.0, 1);
}

TEST(PriorMap, SiteFrame5KilometersAway)
{
  expectQueriesRegister(5000.0, 3);
}

// A scan of another place (KITTI, a road) against the map in a site frame 200 m away
// does not converge.
TEST(PriorMap, KittiScanDoesNotConverge)
{
  PCL_PHASER_REQUIRE_DATA(kDir + "/poses_T_world_lidar.txt");
  PCL_PHASER_REQUIRE_DATA("lidar/kitti_raw_hdl64/0000000000.bin");
  const pcl::phaser::bench::PriorMap map = priorMap(200.0);
  ASSERT_TRUE(map.cloud && !map.cloud->empty());
  pcl::PhaserRegistration<pcl::PointXYZI, pcl::PointXYZI> phaser;
  phaser.setNumberOfThreads(2);
  phaser.setInputTarget(map.cloud);
  phaser.setInputSource(pcl::phaser::test::loadFiniteCloud<pcl::PointXYZI>(
      "lidar/kitti_raw_hdl64/0000000000.bin"));
  Cloud aligned;
  phaser.align(aligned);
  EXPECT_TRUE(phaser.getResult().error.empty()) << phaser.getResult().error;
  EXPECT_FALSE(phaser.hasConverged());
}

// A scan 200 m from its frame origin, and the same scan turned 35 deg about that
// origin: the engine turns each onto its smallest box, so both give the same pose in
// their own axes, and the second's covariance is the first's turned with it (the
// covariance is of left perturbations in the target frame).
TEST(PriorMap, SiteFrameYawTurnsPoseAndCovariance)
{
  PCL_PHASER_REQUIRE_DATA(kDir + "/full36.pcd");
  const Cloud::Ptr source =
      pcl::phaser::test::loadFiniteCloud<pcl::PointXYZI>(kDir + "/full18.pcd");
  const Cloud::Ptr near =
      pcl::phaser::test::loadFiniteCloud<pcl::PointXYZI>(kDir + "/full36.pcd");
  const Eigen::Affine3f shift(Eigen::Translation3f(200.0f, 0.0f, 0.0f));
  const Eigen::Affine3f yaw(
      Eigen::AngleAxisf(35.0f * M_PI / 180.0f, Eigen::Vector3f::UnitZ()));
  Cloud::Ptr moved(new Cloud), turned(new Cloud);
  pcl::transformPointCloud(*near, *moved, shift);
  pcl::transformPointCloud(*near, *turned, yaw * shift);
  const pcl::phaser::PhaserResult a =
      pcl::phaser::test::alignWithDefaults<pcl::PointXYZI>(source, moved);
  const pcl::phaser::PhaserResult b =
      pcl::phaser::test::alignWithDefaults<pcl::PointXYZI>(source, turned);
  ASSERT_TRUE(a.converged && b.converged);
  const Eigen::Matrix4d Q = (yaw.matrix()).cast<double>();
  const Eigen::Matrix4d expected = Q * a.transformation;
  const Eigen::Matrix3d dR = expected.topLeftCorner<3, 3>().transpose() *
                             b.transformation.topLeftCorner<3, 3>();
  EXPECT_LT(Eigen::AngleAxisd(dR).angle() * 180.0 / M_PI, 0.1);
  const Eigen::Vector3d dt =
      expected.topRightCorner<3, 1>() - b.transformation.topRightCorner<3, 1>();
  EXPECT_LT(dt.norm(), 0.02);
  Eigen::Matrix<double, 6, 6> B = Eigen::Matrix<double, 6, 6>::Zero();
  B.topLeftCorner<3, 3>() = Q.topLeftCorner<3, 3>();
  B.bottomRightCorner<3, 3>() = Q.topLeftCorner<3, 3>();
  const Eigen::Matrix<double, 6, 6> turned_back = B * a.covariance * B.transpose();
  EXPECT_LT((b.covariance - turned_back).norm(), 0.02 * b.covariance.norm());
  // Unturned, the covariances differ: the check above can fail.
  EXPECT_GT((b.covariance - a.covariance).norm(), 0.08 * b.covariance.norm());
}

} // namespace
