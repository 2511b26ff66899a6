/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The position prior (PhaserParameters::region_*) on a prior map aggregated from the
 * shared handheld scans: a query whose region holds its true position registers, one
 * whose region excludes it does not converge and stays inside the region.
 */
#include "real_data_support.h"
#include "revisits.h"

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

const std::string kScans = "lidar/balm_handheld/";

/** The points and intensities of scan \a index in the world frame (scan 0's). */
SourceCloud scanCloud(int index, const Eigen::Matrix4d& world_lidar)
{
  const auto cloud = test::loadFiniteCloud<pcl::PointXYZI>(
      kScans + "full" + std::to_string(index) + ".pcd");
  SourceCloud out;
  out.points.resize(3, static_cast<Eigen::Index>(cloud->size()));
  out.channels.assign(1, Eigen::VectorXd(static_cast<Eigen::Index>(cloud->size())));
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    const Eigen::Vector4d p((*cloud)[i].x, (*cloud)[i].y, (*cloud)[i].z, 1.0);
    out.points.col(i) = (world_lidar * p).head<3>();
    out.channels[0](i) = (*cloud)[i].intensity;
  }
  return out;
}

/** A map of every twelfth scan (15 of the 30, about 1.1 M points, unthinned) in the
 *  world frame, and the poses of all scans. */
struct PriorMap {
  std::vector<bench::ScanPose> poses;
  std::unique_ptr<Target> map;
};

const PriorMap& priorMap()
{
  static const PriorMap built = [] {
    PriorMap m;
    std::string error;
    if (!bench::readScanPoses(test::dataPath(kScans + "poses_T_world_lidar.txt"),
                              m.poses, error))
      ADD_FAILURE() << error;
    Eigen::Matrix3Xd points(3, 0);
    Eigen::VectorXd intensity(0);
    for (const bench::ScanPose& pose : m.poses) {
      if (pose.index % 12 != 0)
        continue;
      const SourceCloud scan = scanCloud(pose.index, pose.world_lidar);
      const Eigen::Index n = points.cols();
      points.conservativeResize(3, n + scan.points.cols());
      points.rightCols(scan.points.cols()) = scan.points;
      intensity.conservativeResize(n + scan.points.cols());
      intensity.tail(scan.points.cols()) = scan.channels[0];
    }
    m.map = std::make_unique<Target>(std::move(points), ChannelValues{intensity});
    return m;
  }();
  return built;
}

/** Query scan \a index in its sensor frame and its true T_map_query. */
SourceCloud queryScan(const PriorMap& m, int index, Eigen::Matrix4d& truth)
{
  for (const bench::ScanPose& pose : m.poses)
    if (pose.index == index) {
      truth = pose.world_lidar;
      return scanCloud(index, Eigen::Matrix4d::Identity());
    }
  ADD_FAILURE() << "no pose for scan " << index;
  return {};
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
  void SetUp() override { PCL_PHASER_REQUIRE_DATA(kScans + "poses_T_world_lidar.txt"); }
};

// Queries not in the map (every twelfth scan is); a 10 m region about a point 5 m from
// the truth holds the true position.
TEST_P(RegionPrior, QueryInsideItsRegionRegisters)
{
  const PriorMap& m = priorMap();
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
  const PriorMap& m = priorMap();
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
