/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The position prior (PhaserParameters::region_*) on a prior map aggregated from the
 * shared handheld scans: a query whose region holds its true position registers, one
 * whose region excludes it does not converge and stays inside the region.
 */
#include "prior_map.h"
#include "real_data_support.h"

#include <pcl_phaser/core/pipeline.h>

#include <pcl/point_types.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace pcl::phaser {
namespace {

const std::string kScans = "lidar/balm_handheld";

/** Every twelfth scan (15 of the 30, about 1.1 M points, unthinned) in the world frame
 *  (scan 0's); built once. */
const bench::PriorMap& priorMap()
{
  static const bench::PriorMap built = bench::buildPriorMap(test::dataPath(kScans), 12);
  return built;
}

/** Query scan \a index in its sensor frame and its true T_map_query. */
SourceCloud queryScan(const bench::PriorMap& m, int index, Eigen::Matrix4d& truth)
{
  std::string error;
  const bench::ScanPose* pose = bench::scanPose(m, index);
  if (!pose) {
    ADD_FAILURE() << "no pose for scan " << index;
    return {};
  }
  truth = pose->world_lidar;
  SourceCloud scan = bench::loadScan(test::dataPath(kScans), index,
                                     Eigen::Matrix4d::Identity(), error);
  EXPECT_TRUE(error.empty()) << error;
  return scan;
}

PhaserParameters withRegion(const Eigen::Vector3d& center, double radius)
{
  PhaserParameters params;
  params.num_threads = 2;
  params.region_x = center.x();
  params.region_y = center.y();
  params.region_z = center.z();
  params.region_radius = radius;
  return params;
}

double rotationErrorDeg(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b)
{
  const Eigen::Matrix3d d =
      a.topLeftCorner<3, 3>().transpose() * b.topLeftCorner<3, 3>();
  return Eigen::AngleAxisd(d).angle() * 180.0 / M_PI;
}

class RegionPrior : public ::testing::TestWithParam<int> {
protected:
  void SetUp() override
  {
    PCL_PHASER_REQUIRE_DATA(kScans + "/poses_T_world_lidar.txt");
    ASSERT_TRUE(priorMap().error.empty()) << priorMap().error;
  }
};

// Queries not in the map (every twelfth scan is); a 10 m region about a point 5 m from
// the truth holds the true position.
TEST_P(RegionPrior, QueryInsideItsRegionRegisters)
{
  const bench::PriorMap& m = priorMap();
  Eigen::Matrix4d truth;
  const SourceCloud query = queryScan(m, GetParam(), truth);
  const Eigen::Vector3d center =
      truth.topRightCorner<3, 1>() + Eigen::Vector3d(3.0, -4.0, 0.0);
  const PhaserResult result =
      align(*m.map, query, Eigen::Matrix4d::Identity(), withRegion(center, 10.0));
  ASSERT_TRUE(result.error.empty()) << result.error;
  EXPECT_TRUE(result.converged);
  EXPECT_LT(rotationErrorDeg(result.transformation, truth), 5.0);
  const Eigen::Vector3d error = (result.transformation - truth).topRightCorner<3, 1>();
  EXPECT_LT(error.norm(), 0.6);
  EXPECT_LE((result.transformation.topRightCorner<3, 1>() - center).norm(), 10.0);
}

// The same queries with the region 40 m off: never converged, never outside it.
TEST_P(RegionPrior, RegionExcludingTheTruthDoesNotConverge)
{
  const bench::PriorMap& m = priorMap();
  Eigen::Matrix4d truth;
  const SourceCloud query = queryScan(m, GetParam(), truth);
  const Eigen::Vector3d center =
      truth.topRightCorner<3, 1>() + Eigen::Vector3d(40.0, 0.0, 0.0);
  const PhaserResult result =
      align(*m.map, query, Eigen::Matrix4d::Identity(), withRegion(center, 10.0));
  ASSERT_TRUE(result.error.empty()) << result.error;
  EXPECT_FALSE(result.converged);
  EXPECT_LE((result.transformation.topRightCorner<3, 1>() - center).norm(),
            10.0 + 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Queries, RegionPrior, ::testing::Values(6, 90, 150));

} // namespace
} // namespace pcl::phaser
