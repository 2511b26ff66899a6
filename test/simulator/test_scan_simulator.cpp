// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
// Tests of the LiDAR scan simulator (simulator/scan_simulator.h): determinism, sensor
// geometry, analytic hits and the ground truth of the demo pair.
#include "scan_simulator.h"

#include <pcl/kdtree/kdtree_flann.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

using pcl::phaser::LidarParameters;
using pcl::phaser::makeBox;
using pcl::phaser::makeCylinder;
using pcl::phaser::makeDemoPair;
using pcl::phaser::makeEllipsoid;
using pcl::phaser::makeScanPair;
using pcl::phaser::makeSensorPose;
using pcl::phaser::RayHit;
using pcl::phaser::ScanPair;
using pcl::phaser::SceneParameters;
using pcl::phaser::SimulatedScene;
using Cloud = pcl::PointCloud<pcl::PointXYZI>;

namespace {

constexpr double kPi = 3.14159265358979323846;

/** \brief Same size, and x, y, z, intensity equal bit for bit. */
bool bitIdentical(const Cloud& a, const Cloud& b)
{
  if (a.size() != b.size())
    return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const float fa[4] = {a[i].x, a[i].y, a[i].z, a[i].intensity};
    const float fb[4] = {b[i].x, b[i].y, b[i].z, b[i].intensity};
    if (std::memcmp(fa, fb, sizeof(fa)) != 0)
      return false;
  }
  return true;
}

/** \brief The demo pair of seed 1, computed once (about 60 ms). */
const ScanPair& demoPair()
{
  static const ScanPair pair = makeDemoPair(1);
  return pair;
}

LidarParameters noiseless()
{
  LidarParameters lidar;
  lidar.range_noise = 0.0;
  lidar.intensity_noise = 0.0;
  return lidar;
}

} // namespace

TEST(ScanSimulator, SameParametersGiveBitIdenticalScans)
{
  SceneParameters params;
  params.seed = 3;
  const SimulatedScene scene_a(params), scene_b(params);
  const Eigen::Isometry3d pose = makeSensorPose(1.0, -0.5, 0.7, 0.02, -0.01);
  const Cloud a = scene_a.scan(pose);
  const Cloud b = scene_b.scan(pose);
  ASSERT_GT(a.size(), 0u);
  EXPECT_TRUE(bitIdentical(a, b));
  // A different noise seed changes the returns.
  LidarParameters other;
  other.noise_seed = 8;
  EXPECT_FALSE(bitIdentical(a, scene_a.scan(pose, other)));
  // A different scene seed gives a different scene.
  params.seed = 4;
  EXPECT_FALSE(bitIdentical(a, SimulatedScene(params).scan(pose)));
}

TEST(ScanSimulator, ThreadCountDoesNotChangeTheScan)
{
  const SimulatedScene scene{SceneParameters()};
  const Eigen::Isometry3d pose = makeSensorPose(-1.0, 2.0, -2.0, 0.03, 0.02);
  LidarParameters one, two;
  one.num_threads = 1;
  two.num_threads = 2;
  EXPECT_TRUE(bitIdentical(scene.scan(pose, one), scene.scan(pose, two)));
}

TEST(ScanSimulator, CloudLayoutCountRangeElevationAndIntensity)
{
  const ScanPair& pair = demoPair();
  const LidarParameters lidar;
  for (const Cloud* cloud : {&pair.target, &pair.source}) {
    // 64 beams x 1800 columns = 115200 rays; most of them meet a surface.
    EXPECT_GT(cloud->size(), 80000u);
    EXPECT_LE(cloud->size(), 115200u);
    EXPECT_EQ(cloud->width, cloud->size());
    EXPECT_EQ(cloud->height, 1u);
    EXPECT_TRUE(cloud->is_dense);
    for (const pcl::PointXYZI& p : *cloud) {
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) &&
                  std::isfinite(p.intensity));
      const double range = p.getVector3fMap().cast<double>().norm();
      ASSERT_GE(range, lidar.min_range - 1e-4);
      ASSERT_LE(range, lidar.max_range + 1e-4);
      const double elevation = std::atan2(p.z, std::hypot(p.x, p.y)) * 180.0 / kPi;
      ASSERT_GE(elevation, lidar.min_elevation_deg - 1e-3);
      ASSERT_LE(elevation, lidar.max_elevation_deg + 1e-3);
      ASSERT_GE(p.intensity, 0.0f);
      ASSERT_LE(p.intensity, 1.0f);
    }
  }
}

TEST(ScanSimulator, RangeLimitsAreApplied)
{
  const SimulatedScene scene{SceneParameters()};
  LidarParameters lidar;
  lidar.min_range = 6.0;
  lidar.max_range = 30.0;
  lidar.azimuth_step_deg = 1.0;
  const Cloud cloud = scene.scan(makeSensorPose(0.0, 0.0, 0.0), lidar);
  ASSERT_GT(cloud.size(), 1000u);
  for (const pcl::PointXYZI& p : cloud) {
    const double range = p.getVector3fMap().cast<double>().norm();
    ASSERT_GE(range, 6.0 - 1e-4);
    ASSERT_LE(range, 30.0 + 1e-4);
  }
}

TEST(ScanSimulator, GroundReturnsOfALevelSensorLieAtMinusSensorHeight)
{
  // Ground only: every beam below the horizon that reaches the ground within
  // max_range returns a point at z = -1.8; the others return nothing.
  const SimulatedScene ground(std::vector<pcl::phaser::ScenePrimitive>{}, true);
  LidarParameters lidar = noiseless();
  lidar.azimuth_step_deg = 2.0;
  const Cloud cloud = ground.scan(makeSensorPose(5.0, -7.0, 0.4), lidar);
  int reaching = 0; // beams whose ground hit is within 100 m: tan(-e) >= 1.8 / 100
  for (int b = 0; b < lidar.beams; ++b) {
    const double e = (-24.8 + b * 26.8 / 63.0) * kPi / 180.0;
    reaching += e < 0.0 && 1.8 / std::sin(-e) <= lidar.max_range ? 1 : 0;
  }
  EXPECT_EQ(cloud.size(), static_cast<std::size_t>(reaching) * 180u);
  for (const pcl::PointXYZI& p : cloud)
    ASSERT_NEAR(p.z, -pcl::phaser::kDefaultSensorHeight, 1e-4);

  // In the generated scene the lowest beam sees only ground near the clear center.
  LidarParameters low = noiseless();
  low.beams = 1;
  const SimulatedScene scene{SceneParameters()};
  const Cloud ring = scene.scan(makeSensorPose(0.0, 0.0, 1.0), low);
  EXPECT_EQ(ring.size(), 1800u);
  for (const pcl::PointXYZI& p : ring)
    ASSERT_NEAR(p.z, -1.8, 1e-4);
}

TEST(ScanSimulator, AnalyticDistancesToPrimitives)
{
  const double yaw = 30.0 * kPi / 180.0;
  const Eigen::Vector3d yawed_center(10.0, -20.0, 1.0);
  const SimulatedScene scene(
      {makeBox({12.0, 0.0, 2.0}, {2.0, 3.0, 2.0}, 0.0, 0.5),
       makeBox(yawed_center, {1.0, 2.0, 1.0}, yaw, 0.6),
       makeCylinder(-5.0, 0.0, 0.0, 4.0, 0.5, 0.8),
       makeEllipsoid({0.0, 8.0, 1.0}, {1.0, 2.0, 0.5}, 0.5 * kPi, 0.4)},
      false);
  RayHit hit;
  // Straight at the box's front face x = 10.
  ASSERT_TRUE(scene.castRay({0.0, 0.0, 1.0}, {1.0, 0.0, 0.0}, 100.0, hit));
  EXPECT_NEAR(hit.range, 10.0, 1e-12);
  EXPECT_EQ(hit.primitive, 0);
  EXPECT_NEAR(hit.normal.x(), -1.0, 1e-12);
  EXPECT_DOUBLE_EQ(hit.reflectivity, 0.5);
  // A yawed box, along its local x axis towards its center: face at 1 m from it.
  const Eigen::Vector3d axis(std::cos(yaw), std::sin(yaw), 0.0);
  ASSERT_TRUE(scene.castRay(yawed_center + 6.0 * axis, -axis, 100.0, hit));
  EXPECT_NEAR(hit.range, 5.0, 1e-9);
  EXPECT_NEAR((hit.normal - axis).norm(), 0.0, 1e-9);
  // Cylinder of radius 0.5 at x = -5, and its top cap from above.
  ASSERT_TRUE(scene.castRay({0.0, 0.0, 1.0}, {-1.0, 0.0, 0.0}, 100.0, hit));
  EXPECT_NEAR(hit.range, 4.5, 1e-9);
  ASSERT_TRUE(scene.castRay({-5.1, 0.0, 10.0}, {0.0, 0.0, -1.0}, 100.0, hit));
  EXPECT_NEAR(hit.range, 6.0, 1e-9);
  EXPECT_NEAR(hit.normal.z(), 1.0, 1e-12);
  // Ellipsoid yawed by 90 degrees: its local x semi-axis (1 m) lies along world y.
  ASSERT_TRUE(scene.castRay({0.0, 0.0, 1.0}, {0.0, 1.0, 0.0}, 100.0, hit));
  EXPECT_NEAR(hit.range, 7.0, 1e-9);
  // Out of range, and a miss (no ground).
  EXPECT_FALSE(scene.castRay({0.0, 0.0, 1.0}, {1.0, 0.0, 0.0}, 9.5, hit));
  EXPECT_FALSE(scene.castRay({0.0, 0.0, 1.0}, {0.0, -1.0, 0.0}, 100.0, hit));

  // One horizontal beam through a scan: every return on the front face lies at x = 10.
  LidarParameters flat = noiseless();
  flat.beams = 1;
  flat.min_elevation_deg = flat.max_elevation_deg = 0.0;
  flat.azimuth_step_deg = 1.0;
  const Cloud cloud = scene.scan(makeSensorPose(0.0, 0.0, 0.0, 0.0, 0.0, 1.0), flat);
  int on_face = 0;
  for (const pcl::PointXYZI& p : cloud)
    if (p.x > 9.0 && std::abs(p.y) < 3.5) { // not the yawed box at y = -20
      EXPECT_NEAR(p.x, 10.0, 1e-5);
      EXPECT_NEAR(p.z, 0.0, 1e-6);
      ++on_face;
    }
  EXPECT_EQ(on_face, 33); // azimuths -16..16 degrees: |tan| <= 3 / 10
  ASSERT_FALSE(cloud.empty());
  EXPECT_EQ(cloud[0].x, 10.0f); // column 0 looks along +x
  EXPECT_EQ(cloud[0].y, 0.0f);
}

TEST(ScanSimulator, FreePositions)
{
  const SimulatedScene scene({makeBox({12.0, 0.0, 2.0}, {2.0, 3.0, 2.0}, 0.0, 0.5)});
  EXPECT_TRUE(scene.isFree({0.0, 0.0, 1.8}));
  EXPECT_FALSE(scene.isFree({12.0, 0.0, 1.0}));      // inside
  EXPECT_FALSE(scene.isFree({9.5, 0.0, 1.8}));       // 0.5 m from the face
  EXPECT_TRUE(scene.isFree({9.5, 0.0, 1.8}, 0.4));   // ... enough for 0.4 m
  EXPECT_FALSE(scene.isFree({0.0, 0.0, -1.0}, 0.1)); // under the ground
}

TEST(ScanSimulator, DemoPairTruthIsExactAndLarge)
{
  const ScanPair& pair = demoPair();
  const Eigen::Matrix4d expected =
      (pair.target_pose.inverse() * pair.source_pose).matrix();
  EXPECT_TRUE(pair.T_target_source.isApprox(expected, 1e-12));
  const Eigen::Matrix3d rotation = pair.T_target_source.topLeftCorner<3, 3>();
  EXPECT_NEAR((rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm(),
              0.0, 1e-12);
  const double angle = Eigen::AngleAxisd(rotation).angle() * 180.0 / kPi;
  EXPECT_GT(angle, 95.0);
  EXPECT_LT(angle, 165.0);
  const double offset = pair.T_target_source.topRightCorner<3, 1>().norm();
  EXPECT_GE(offset, 2.0 - 1e-9);
  EXPECT_LE(offset, 4.0 + 1e-9);
  EXPECT_NEAR(pair.target_pose.translation().z(), 1.8, 1e-12);
  EXPECT_NEAR(pair.source_pose.translation().z(), 1.8, 1e-12);
  // Same seed, same pair.
  EXPECT_TRUE(bitIdentical(pair.source, makeDemoPair(1).source));
}

TEST(ScanSimulator, DemoPairSourceLandsOnTheTargetSurfaces)
{
  // Noise-free demo pair; a dense reference scan from the target pose stands for "the
  // surfaces the target sees" (the sparse rings of the far ground differ from scan to
  // scan, so only source points within 20 m are compared).
  SceneParameters params;
  params.seed = 1;
  const SimulatedScene scene(params);
  const ScanPair& demo = demoPair();
  const LidarParameters lidar = noiseless();
  const ScanPair pair = makeScanPair(scene, demo.target_pose, demo.source_pose, lidar);
  LidarParameters dense = lidar;
  dense.beams = 512;
  dense.azimuth_step_deg = 0.1;
  const Cloud::Ptr reference(new Cloud(scene.scan(demo.target_pose, dense)));
  pcl::KdTreeFLANN<pcl::PointXYZI> tree;
  tree.setInputCloud(reference);

  // Fraction of the source points (every 7th, within 20 m of the source sensor and
  // inside the target's beam fan) that land within 0.3 m of a reference point.
  const auto fractionClose = [&](const Eigen::Matrix4f& transform, int& checked) {
    std::vector<int> index(1);
    std::vector<float> sq_distance(1);
    int close = 0;
    checked = 0;
    for (std::size_t i = 0; i < pair.source.size(); i += 7) {
      const Eigen::Vector3f p = pair.source[i].getVector3fMap();
      if (p.norm() > 20.0f)
        continue;
      pcl::PointXYZI q;
      q.getVector3fMap() =
          transform.topLeftCorner<3, 3>() * p + transform.topRightCorner<3, 1>();
      // The target cannot see the ground right around itself (below its lowest beam).
      const double elevation = std::atan2(q.z, std::hypot(q.x, q.y)) * 180.0 / kPi;
      if (elevation < lidar.min_elevation_deg + 0.1 ||
          elevation > lidar.max_elevation_deg - 0.1)
        continue;
      if (tree.nearestKSearch(q, 1, index, sq_distance) != 1)
        continue;
      ++checked;
      close += sq_distance[0] < 0.3f * 0.3f ? 1 : 0;
    }
    return checked > 0 ? static_cast<double>(close) / checked : 0.0;
  };
  int checked = 0;
  const Eigen::Matrix4f truth = pair.T_target_source.cast<float>();
  const double fraction = fractionClose(truth, checked);
  EXPECT_GT(checked, 3000);
  EXPECT_GT(fraction, 0.95) << checked << " points checked"; // 99.7% in practice

  // A slightly wrong transform (the truth tilted by 3 degrees about x) fails it
  // (about 70% close).
  Eigen::Matrix4f wrong = Eigen::Matrix4f::Identity();
  wrong.topLeftCorner<3, 3>() =
      Eigen::AngleAxisf(3.0f * static_cast<float>(kPi) / 180.0f,
                        Eigen::Vector3f::UnitX())
          .toRotationMatrix();
  EXPECT_LT(fractionClose(wrong * truth, checked), 0.8);
}
