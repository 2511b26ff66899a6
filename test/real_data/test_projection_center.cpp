/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * ProjectionCenter::Automatic on the shared scans: it must pick the sensor origin for
 * LiDAR scans in their sensor frame and the centroid for objects and depth-camera
 * frames, and the registrations it then runs must succeed.
 */
#include "../registration/test_data.h"
#include "cloud_reading.h"
#include "pipeline/projection_center.h"
#include "protocol.h"
#include "real_data_support.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>
#include <pcl/filters/filter.h>
#include <pcl/point_types.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace {

using CloudXYZ = pcl::PointCloud<pcl::PointXYZ>;
using Phaser = pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ>;
using Center = Phaser::ProjectionCenter;

CloudXYZ::Ptr loadFinite(const std::string& relative)
{
  return pcl::phaser::test::loadFiniteCloud<pcl::PointXYZ>(relative);
}

Eigen::Matrix3Xd matrix(const CloudXYZ& cloud)
{
  Eigen::Matrix3Xd points(3, cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    points.col(static_cast<Eigen::Index>(i)) = cloud[i].getVector3fMap().cast<double>();
  return points;
}

const char* name(Center c)
{
  return c == Center::SensorOrigin ? "sensor origin" : "centroid";
}

/** The scan seen again from \a poses random poses (the end-to-end protocol), registered
 * in Automatic mode; returns the successes. The moved source's sensor sits up to 2 m
 * from its origin, so either center may be chosen; both must work. */
int automaticRandomPoses(const std::string& relative, int poses)
{
  const CloudXYZ::Ptr scan = loadFinite(relative);
  std::mt19937 rng(7);
  int ok = 0;
  for (int k = 0; k < poses; ++k) {
    const Eigen::Matrix4d T = pcl::phaser::bench::randomPose(rng, 2.0);
    auto source = pcl::make_shared<CloudXYZ>();
    pcl::transformPointCloud(*scan, *source, Eigen::Matrix4d(T.inverse()));
    Phaser phaser;
    phaser.setNumberOfThreads(2);
    phaser.setProjectionCenter(Center::Automatic);
    phaser.setInputSource(source);
    phaser.setInputTarget(scan);
    CloudXYZ aligned;
    phaser.align(aligned);
    const Eigen::Matrix4d G = phaser.getFinalTransformation().cast<double>();
    const double r = pcl::phaser::bench::rreDeg(G, T),
                 t = pcl::phaser::bench::rteM(G, T);
    std::printf("  %s pose %d: %s, RRE %.3f deg, RTE %.3f m\n", relative.c_str(), k,
                name(phaser.getResult().projection_center), r, t);
    ok += phaser.hasConverged() && r < 2.0 && t < 0.3;
  }
  return ok;
}

/** One registration in Automatic mode, which must converge and choose \a expected;
 * returns the estimate. */
Eigen::Matrix4d alignAutomatic(const CloudXYZ::Ptr& source, const CloudXYZ::Ptr& target,
                               Center expected)
{
  Phaser phaser;
  phaser.setProjectionCenter(Center::Automatic);
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  CloudXYZ out;
  phaser.align(out);
  EXPECT_TRUE(phaser.hasConverged());
  EXPECT_EQ(phaser.getResult().projection_center, expected);
  return phaser.getFinalTransformation().cast<double>();
}

} // namespace

TEST(AutomaticCenter, SeparatesSensorFramesFromObjectsCamerasAndRooms)
{
  // Coverage: the threshold 0.2 lies between the lowest LiDAR scan (cloud049, 0.26) and
  // the highest object or camera frame (bun0, 0.15). Polar fraction: LiDAR scans see
  // nothing within 45 deg of their band's poles, the office keypoints 2-3 % (floor and
  // ceiling).
  PCL_PHASER_REQUIRE_DATA("lidar/kitti_synthetic_gt/cloud049.ply");
  PCL_PHASER_REQUIRE_DATA("pcl/frame_20121214T142255.814212.pcd");
  const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  for (const char* lidar :
       {"lidar/hdl32_fastgicp/251370668.pcd", "lidar/hdl32_fastgicp/251371071.pcd",
        "lidar/kitti_raw_hdl64/0000000000.bin", "lidar/kitti_synthetic_gt/cloud049.ply",
        "lidar/kitti_synthetic_gt/cloud050.ply"}) {
    const Eigen::Matrix3Xd p = matrix(*loadFinite(lidar));
    const double c = pcl::phaser::viewCoverage(p, origin);
    const double polar = pcl::phaser::polarFraction(p, origin);
    std::printf("  %-45s coverage %.3f polar %.4f\n", lidar, c, polar);
    EXPECT_GE(c, pcl::phaser::kSensorFrameCoverage + 0.05) << lidar;
    EXPECT_LE(polar, pcl::phaser::kSensorFramePolarFraction / 5) << lidar;
    EXPECT_TRUE(pcl::phaser::looksSensorCentered(p, origin)) << lidar;
  }
  for (const char* object :
       {"pcl/bun0.pcd", "pcl/bun4.pcd", "object/stanford_bunny/bun000.ply",
        "object/stanford_bunny/bun045.ply", "pcl/frame_20121214T142255.814212.pcd",
        "pcl/frame_20121214T142256.068683.pcd"}) {
    const double c = pcl::phaser::viewCoverage(matrix(*loadFinite(object)), origin);
    std::printf("  %-45s coverage %.3f\n", object, c);
    EXPECT_LE(c, pcl::phaser::kSensorFrameCoverage - 0.04) << object;
  }
  for (const char* room : {"pcl/office1_keypoints.pcd", "pcl/office2_keypoints.pcd"}) {
    const double polar = pcl::phaser::polarFraction(matrix(*loadFinite(room)), origin);
    std::printf("  %-45s polar %.4f\n", room, polar);
    EXPECT_GE(polar, 3 * pcl::phaser::kSensorFramePolarFraction) << room;
  }
}

TEST(AutomaticCenter, LidarScansUnderRandomPoses)
{
  PCL_PHASER_REQUIRE_DATA("lidar/hdl32_fastgicp/251370668.pcd");
  PCL_PHASER_REQUIRE_DATA("lidar/kitti_raw_hdl64/0000000000.bin");
  EXPECT_EQ(automaticRandomPoses("lidar/hdl32_fastgicp/251370668.pcd", 4), 4);
  EXPECT_EQ(automaticRandomPoses("lidar/kitti_raw_hdl64/0000000000.bin", 4), 4);
}

TEST(AutomaticCenter, KinectFrameUsesTheCentroid)
{
  // A 57 x 43 deg camera frame: its centroid (about the
  // sensor origin range-only registration succeeds 3/5, about the centroid 5/5).
  PCL_PHASER_REQUIRE_DATA("pcl/frame_20121214T142255.814212.pcd");
  EXPECT_EQ(automaticRandomPoses("pcl/frame_20121214T142255.814212.pcd", 3), 3);
}

TEST(AutomaticCenter, SacIaPatternUsesTheCentroid)
{
  // PCL's test_sac_ia set-up: bun0 moved by 100 m and yawed by 90 deg, aligned to bun4.
  // The target surrounds its origin a little (0.13), the moved source not at all.
  PCL_PHASER_REQUIRE_DATA("pcl/bun4.pcd");
  const auto bun0 = loadFinite("pcl/bun0.pcd");
  const auto target = loadFinite("pcl/bun4.pcd");
  Eigen::Matrix4d move = Eigen::Matrix4d::Identity();
  move.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
  move(0, 3) = 100.0;
  auto source = pcl::make_shared<CloudXYZ>();
  pcl::transformPointCloud(*bun0, *source, move);
  Phaser automatic, centroid;
  centroid.setProjectionCenter(Center::Centroid);
  automatic.setProjectionCenter(Center::Automatic);
  CloudXYZ out;
  for (Phaser* p : {&automatic, &centroid}) {
    p->setInputSource(source);
    p->setInputTarget(target);
    p->align(out);
    ASSERT_TRUE(p->hasConverged());
  }
  EXPECT_EQ(automatic.getResult().projection_center, Center::Centroid);
  EXPECT_EQ(centroid.getResult().projection_center, Center::Centroid);
  EXPECT_TRUE(automatic.getFinalTransformation().isApprox(
      centroid.getFinalTransformation(), 1e-6f));
}

TEST(AutomaticCenter, OfficeKeypointsUseTheCentroid)
{
  // Keypoints of two office scans: they surround their origins (coverage 0.39-0.45) but
  // also see floor and ceiling. About the origins the registration does not converge;
  // about the centroids it meets PCL's tolerance (0.1745 rad, 1 m).
  PCL_PHASER_REQUIRE_DATA("pcl/office2_keypoints.pcd");
  const auto source = loadFinite("pcl/office1_keypoints.pcd");
  const auto target = loadFinite("pcl/office2_keypoints.pcd");
  Eigen::Matrix4d truth = Eigen::Matrix4d::Identity();
  truth.topRows<3>() << -0.6946, -0.7194, -0.0051, -3.6352, 0.7194, -0.6945, -0.0100,
      -2.3865, 0.0037, -0.0106, 0.9999, 0.7778;
  const Eigen::Matrix4d G = alignAutomatic(source, target, Center::Centroid);
  std::printf("  office, centroid: RRE %.3f deg, RTE %.3f m\n",
              pcl::phaser::bench::rreDeg(G, truth), pcl::phaser::bench::rteM(G, truth));
  EXPECT_LT(pcl::phaser::bench::rreDeg(G, truth) * M_PI / 180.0, 0.1745);
  EXPECT_LT(pcl::phaser::bench::rteM(G, truth), 1.0);
}
