/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The position prior (PhaserParameters::region) on an unthinned prior map of every
 * other balm_handheld scan (1.13 M points, scan 0's frame): a query whose 10 m region
 * holds its true position registers; one whose region lies 40 m away does not converge
 * and its pose stays inside the region.
 */
#include "prior_map.h"
#include "real_data_support.h"

#include <pcl_phaser/phaser_registration.h>

#include <Eigen/Geometry>

#include <string>

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZI>;
const std::string kDir = "lidar/balm_handheld";

/** The unthinned map, built once. */
const pcl::phaser::bench::PriorMap& priorMap()
{
  static const pcl::phaser::bench::PriorMap map = [] {
    pcl::phaser::bench::PriorMap m;
    std::string error;
    if (!pcl::phaser::bench::buildPriorMap(pcl::phaser::test::dataPath(kDir), 2, 0.0,
                                           Eigen::Matrix4d::Identity(), m, error))
      ADD_FAILURE() << error;
    return m;
  }();
  return map;
}

/** Query scan \a index registered onto the map with a region of \a radius about its
 *  true position + \a offset; \a truth: T_map_query, \a center: the region's. */
pcl::phaser::PhaserResult alignInRegion(int index, const Eigen::Vector3d& offset,
                                        double radius, Eigen::Matrix4d& truth,
                                        Eigen::Vector3d& center)
{
  const pcl::phaser::bench::PriorMap& map = priorMap();
  truth = map.world_lidar.at(index);
  center = truth.topRightCorner<3, 1>() + offset;
  pcl::PhaserRegistration<pcl::PointXYZI, pcl::PointXYZI> phaser;
  pcl::phaser::PhaserParameters params = phaser.getParameters();
  params.num_threads = 2;
  params.region = pcl::phaser::Region{center.x(), center.y(), center.z(), radius};
  phaser.setParameters(params);
  phaser.setInputTarget(map.cloud);
  phaser.setInputSource(pcl::phaser::test::loadFiniteCloud<pcl::PointXYZI>(
      kDir + "/full" + std::to_string(index) + ".pcd"));
  Cloud aligned;
  phaser.align(aligned);
  return phaser.getResult();
}

class RegionPrior : public ::testing::TestWithParam<int> {
protected:
  void SetUp() override
  {
    PCL_PHASER_REQUIRE_DATA(kDir + "/poses_T_world_lidar.txt");
    ASSERT_TRUE(priorMap().cloud && priorMap().cloud->size() > 1000000);
  }
};

// Queries 6, 90, 150 are not in the map; the region's center is 5 m from the truth.
TEST_P(RegionPrior, QueryInsideItsRegionRegisters)
{
  Eigen::Matrix4d truth;
  Eigen::Vector3d center;
  const pcl::phaser::PhaserResult result =
      alignInRegion(GetParam(), Eigen::Vector3d(3.0, -4.0, 0.0), 10.0, truth, center);
  ASSERT_TRUE(result.error.empty()) << result.error;
  EXPECT_TRUE(result.converged);
  const Eigen::Matrix3d dR = result.transformation.topLeftCorner<3, 3>().transpose() *
                             truth.topLeftCorner<3, 3>();
  EXPECT_LT(Eigen::AngleAxisd(dR).angle() * 180.0 / M_PI, 5.0);
  const Eigen::Vector3d error = (result.transformation - truth).topRightCorner<3, 1>();
  EXPECT_LT(error.norm(), 0.6);
  EXPECT_LE((result.transformation.topRightCorner<3, 1>() - center).norm(), 10.0);
}

// The region 40 m off: never converged, never outside.
TEST_P(RegionPrior, RegionExcludingTheTruthDoesNotConverge)
{
  Eigen::Matrix4d truth;
  Eigen::Vector3d center;
  const pcl::phaser::PhaserResult result =
      alignInRegion(GetParam(), Eigen::Vector3d(40.0, 0.0, 0.0), 10.0, truth, center);
  ASSERT_TRUE(result.error.empty()) << result.error;
  EXPECT_FALSE(result.converged);
  EXPECT_LE((result.transformation.topRightCorner<3, 1>() - center).norm(),
            10.0 + 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Queries, RegionPrior, ::testing::Values(6, 90, 150));

} // namespace
