/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Objects: partial range scans of the Stanford bunny registered with the class
 * default-constructed, as SAC-IA is used, must be right and converged; pairs that share
 * nothing (the bunny's front against its back, a milk carton against a bunny view) must
 * not converge. Truth from Stanford's bun.conf: p_bun000 = R(q)^T p + t.
 */
#include "real_data_support.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>
#include <pcl/point_types.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace {

using CloudXYZ = pcl::PointCloud<pcl::PointXYZ>;
using Phaser = pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ>;

const std::string kBunny = "object/stanford_bunny/";

/** T_bun000_view of every view of bun.conf, by name without ".ply". */
std::map<std::string, Eigen::Matrix4d> bunnyPoses()
{
  std::map<std::string, Eigen::Matrix4d> poses;
  std::ifstream in(pcl::phaser::test::dataPath(kBunny + "bun.conf"));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string kind, file;
    double tx, ty, tz, qx, qy, qz, qw;
    if (!(fields >> kind >> file >> tx >> ty >> tz >> qx >> qy >> qz >> qw) ||
        kind != "bmesh")
      continue;
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    T.topLeftCorner<3, 3>() =
        Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix().transpose();
    T.topRightCorner<3, 1>() = Eigen::Vector3d(tx, ty, tz);
    poses[file.substr(0, file.size() - 4)] = T;
  }
  return poses;
}

struct Outcome {
  bool converged = false;
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
};

Outcome align(const std::string& source, const std::string& target)
{
  Phaser phaser;
  phaser.setNumberOfThreads(2);
  phaser.setInputSource(pcl::phaser::test::loadFiniteCloud<pcl::PointXYZ>(source));
  phaser.setInputTarget(pcl::phaser::test::loadFiniteCloud<pcl::PointXYZ>(target));
  CloudXYZ aligned;
  phaser.align(aligned);
  return {phaser.hasConverged(), phaser.getFinalTransformation().cast<double>()};
}

/** Rotation (deg) and translation (m) errors of \a T against \a truth. */
std::pair<double, double> errors(const Eigen::Matrix4d& T, const Eigen::Matrix4d& truth)
{
  const Eigen::Matrix4d E = truth.inverse() * T;
  const double angle =
      Eigen::AngleAxisd(Eigen::Matrix3d(E.topLeftCorner<3, 3>())).angle();
  return {angle * 180.0 / M_PI,
          (T.topRightCorner<3, 1>() - truth.topRightCorner<3, 1>()).norm()};
}

} // namespace

// The easiest pair (34 deg, 94 % of the source seen again) once flipped by 178.6 deg:
// no rotation hypothesis about either center lay within 18 deg of the truth
// (doc/method.md, section 4). Measured: 0.1 deg / 0.1 mm both.
TEST(Objects, BunnyViewsAreRightAndConverged)
{
  for (const char* view : {"bun000", "bun045", "bun315"})
    PCL_PHASER_REQUIRE_DATA(kBunny + view + ".ply");
  const auto poses = bunnyPoses();
  ASSERT_EQ(poses.count("bun045") + poses.count("bun315"), 2u);
  const std::pair<const char*, const char*> pairs[] = {{"bun045", "bun000"},
                                                       {"bun000", "bun315"}};
  for (const auto& [source, target] : pairs) {
    const Outcome out = align(kBunny + source + ".ply", kBunny + target + ".ply");
    const auto [rotation, translation] =
        errors(out.T, poses.at(target).inverse() * poses.at(source));
    EXPECT_TRUE(out.converged) << source << " -> " << target;
    EXPECT_LT(rotation, 2.0) << source << " -> " << target;
    EXPECT_LT(translation, 0.002) << source << " -> " << target;
  }
}

TEST(Objects, SwappedViewsGiveTheInverse)
{
  PCL_PHASER_REQUIRE_DATA(kBunny + "bun000.ply");
  PCL_PHASER_REQUIRE_DATA(kBunny + "bun045.ply");
  const Outcome forward = align(kBunny + "bun045.ply", kBunny + "bun000.ply");
  const Outcome backward = align(kBunny + "bun000.ply", kBunny + "bun045.ply");
  const auto [rotation, translation] = errors(backward.T, forward.T.inverse());
  EXPECT_TRUE(forward.converged && backward.converged);
  EXPECT_LT(rotation, 1.0);
  EXPECT_LT(translation, 0.002);
}

// Nothing shared: front against back (0.4 % of bun000 within 2 mm of bun180 after the
// truth) and a milk carton against a bunny view. A compact object matches about a fifth
// of any other at the verification radius, so only a pose that stands out may claim.
TEST(Objects, UnrelatedObjectsDoNotConverge)
{
  PCL_PHASER_REQUIRE_DATA(kBunny + "bun000.ply");
  PCL_PHASER_REQUIRE_DATA(kBunny + "bun180.ply");
  PCL_PHASER_REQUIRE_DATA("pcl/milk.pcd");
  EXPECT_FALSE(align(kBunny + "bun000.ply", kBunny + "bun180.ply").converged);
  EXPECT_FALSE(align("pcl/milk.pcd", kBunny + "bun000.ply").converged);
  EXPECT_FALSE(align(kBunny + "bun000.ply", "pcl/milk.pcd").converged);
}

namespace {

/** The milk carton model moved by a fixed pose, with the truth that undoes it: the
 *  model is cut out of the scene (all its points lie on scene points, median distance
 *  0), so the identity is exact before the move. */
std::pair<CloudXYZ::Ptr, Eigen::Matrix4d> movedCarton()
{
  const CloudXYZ::Ptr model =
      pcl::phaser::test::loadFiniteCloud<pcl::PointXYZ>("pcl/milk.pcd");
  Eigen::Matrix4d move = Eigen::Matrix4d::Identity();
  move.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(2.0, Eigen::Vector3d(0.3, -0.8, 0.5).normalized())
          .toRotationMatrix();
  move.topRightCorner<3, 1>() = Eigen::Vector3d(0.4, -0.3, 0.2);
  auto moved = pcl::make_shared<CloudXYZ>();
  pcl::transformPointCloud(*model, *moved, move.cast<float>());
  return {moved, move.inverse()};
}

/** The scene's points within \a radius of \a center (as pcl::CropBox would keep). */
CloudXYZ::Ptr cropped(const CloudXYZ& scene, const Eigen::Vector3f& center,
                      float radius)
{
  auto out = pcl::make_shared<CloudXYZ>();
  for (const auto& p : scene)
    if ((p.getVector3fMap() - center).norm() < radius)
      out->push_back(p);
  return out;
}

} // namespace

// A model in a cluttered Kinect scene (PCL's correspondence-grouping pair): against the
// whole scene every spectrum is the scene's (the carton is 6 % of its points), no
// rotation hypothesis comes within 79 deg and nothing is claimed; with the scene
// cropped to where the object is (the hint, doc/tutorial.md), it is an object pair
// again.
TEST(Objects, ModelInAClutteredSceneNeedsACrop)
{
  PCL_PHASER_REQUIRE_DATA("pcl/milk.pcd");
  PCL_PHASER_REQUIRE_DATA("pcl/milk_cartoon_all_small_clorox.pcd");
  const auto scene = pcl::phaser::test::loadFiniteCloud<pcl::PointXYZ>(
      "pcl/milk_cartoon_all_small_clorox.pcd");
  const auto [carton, truth] = movedCarton();
  const Eigen::Vector3f at(-0.056f, -0.137f,
                           0.774f); // the carton's centroid in the scene
  for (const bool crop : {false, true}) {
    Phaser phaser;
    phaser.setNumberOfThreads(2);
    phaser.setInputSource(carton);
    phaser.setInputTarget(crop ? cropped(*scene, at, 0.2f) : scene);
    CloudXYZ aligned;
    phaser.align(aligned);
    const auto [rotation, translation] =
        errors(phaser.getFinalTransformation().cast<double>(), truth);
    EXPECT_EQ(phaser.hasConverged(), crop);
    if (crop) {
      EXPECT_LT(rotation, 2.0);
      EXPECT_LT(translation, 0.005);
    }
  }
}
