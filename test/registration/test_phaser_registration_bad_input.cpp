/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Every bad input of PhaserRegistration: refused with PCL_ERROR, never converged, the
 * final transformation left at the guess, no crash.
 */
#include "registration_test_scene.h"

#include <pcl_phaser/phaser_registration.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace registration_test;

// ---------------------------------------------------------------------------------------
// Bad input: PCL_ERROR, hasConverged() == false, final transformation == guess, no
// crash.

namespace {

void expectRejected(pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ>& phaser,
                    const CloudXYZ::Ptr& source, const CloudXYZ::Ptr& target)
{
  const Eigen::Matrix4f guess = makePose({0, 0, 1}, 0.3, {1, 2, 3});
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  CloudXYZ out;
  phaser.align(out, guess);
  EXPECT_FALSE(phaser.hasConverged());
  EXPECT_TRUE(phaser.getFinalTransformation() == guess);
  (void)phaser.getFitnessScore(); // must not abort on NaN points
}

CloudXYZ::Ptr cloudOf(std::initializer_list<pcl::PointXYZ> points)
{
  auto c = pcl::make_shared<CloudXYZ>();
  for (const auto& p : points)
    c->push_back(p);
  return c;
}

} // namespace

TEST(PhaserRegistrationBadInput, EmptyClouds)
{
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
  const auto scene = makeScene<pcl::PointXYZ>();
  auto empty = pcl::make_shared<CloudXYZ>();
  phaser.setInputSource(empty); // PCL rejects it: no source
  phaser.setInputTarget(scene);
  CloudXYZ out;
  phaser.align(out);
  EXPECT_FALSE(phaser.hasConverged());
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> other;
  other.setInputSource(scene);
  other.setInputTarget(empty); // PCL rejects it: no target
  other.align(out);
  EXPECT_FALSE(other.hasConverged());
}

TEST(PhaserRegistrationBadInput, AllNaN)
{
  const float nan = std::numeric_limits<float>::quiet_NaN();
  auto nan_cloud = cloudOf({{nan, nan, nan}, {nan, 1, 2}, {3, nan, 4}});
  nan_cloud->is_dense = false;
  const auto scene = makeScene<pcl::PointXYZ>();
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> a, b;
  expectRejected(a, nan_cloud, scene);
  expectRejected(b, scene, nan_cloud);
}

TEST(PhaserRegistrationBadInput, SinglePointAndDuplicates)
{
  const auto scene = makeScene<pcl::PointXYZ>();
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> a, b, c;
  expectRejected(a, cloudOf({{1, 2, 3}}), scene);
  expectRejected(b, scene, cloudOf({{1, 2, 3}}));
  expectRejected(c, cloudOf({{1, 2, 3}, {1, 2, 3}, {1, 2, 3}}), scene);
}

TEST(PhaserRegistrationBadInput, AllPointsAtTheCenter)
{
  const auto scene = makeScene<pcl::PointXYZ>();
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> a;
  expectRejected(a, cloudOf({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}), scene);
}

TEST(PhaserRegistrationBadInput, HugeCoordinates)
{
  // 1e7 m: float32 spacing is 1 m there. Rejected in both center modes, either side.
  auto huge = makeScene<pcl::PointXYZ>();
  for (auto& p : *huge)
    p.x += 1e7f;
  const auto scene = makeScene<pcl::PointXYZ>();
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> a, b, c;
  expectRejected(a, huge, scene);
  expectRejected(b, scene, huge);
  c.setProjectionCenter(decltype(c)::ProjectionCenter::Centroid);
  expectRejected(c, huge, scene);
}

TEST(PhaserRegistrationBadInput, ParametersOutOfRange)
{
  const auto scene = makeScene<pcl::PointXYZ>();
  const auto source = seenFrom(*scene, makePose({0, 0, 1}, 0.5, {0, 0, 0}));
  // The setters refuse an illegal value at once and keep the defaults
  // (test_parameter_messages.cpp); a voxel size too fine for the clouds is refused at
  // align().
  auto check = [&](auto&& configure) {
    pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
    configure(phaser);
    EXPECT_EQ(pcl::phaser::validateParameters(phaser.getParameters()), "");
    EXPECT_EQ(phaser.getBandwidth(), pcl::phaser::PhaserParameters().bandwidth);
    if (phaser.getParameters().voxel_size > 0.0)
      expectRejected(phaser, source, scene);
  };
  auto setting = [&](auto&& change) {
    check([&](auto& phaser) {
      pcl::phaser::PhaserParameters q = phaser.getParameters();
      change(q);
      phaser.setParameters(q);
    });
  };
  check([](auto& p) { p.setBandwidth(0); });
  check([](auto& p) { p.setBandwidth(1000); });
  setting([](auto& q) { q.spatial_grid_size = 0; });
  setting([](auto& q) { q.spatial_grid_size = 10000; });
  setting([](auto& q) { q.voxel_size = -1.0; });
  setting([](auto& q) { q.voxel_size = std::numeric_limits<double>::quiet_NaN(); });
  setting([](auto& q) { q.voxel_size = 1e-6; }); // would need 10^7 voxels per axis
  setting([](auto& q) { q.refinement_iterations = -1; });
  setting([](auto& q) { q.refinement_iterations = 11; });
  setting([](auto& q) { q.rotation_candidates = 0; });
  setting([](auto& q) { q.passes = 6; });
  setting([](auto& q) { q.fusion_levels = 0; });
  setting([](auto& q) { q.orientation_candidates = 21; });
  setting([](auto& q) { q.whitening = 1.5; });
  check([](auto& p) { p.setNumberOfThreads(100000); });
  setting([](auto& q) { q.min_peak_score = -1.0; });
  setting([](auto& q) { q.min_normalized_overlap = -0.1; });
  setting([](auto& q) { q.min_normalized_overlap = 1.5; });
  setting([](auto& q) {
    q.min_normalized_overlap = std::numeric_limits<double>::quiet_NaN();
  });
}

TEST(PhaserRegistrationBadInput, NonFiniteGuess)
{
  const auto scene = makeScene<pcl::PointXYZ>();
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
  phaser.setInputSource(scene);
  phaser.setInputTarget(scene);
  Eigen::Matrix4f guess = Eigen::Matrix4f::Identity();
  guess(0, 3) = std::numeric_limits<float>::infinity();
  CloudXYZ out;
  phaser.align(out, guess);
  EXPECT_FALSE(phaser.hasConverged());
}

TEST(PhaserRegistrationBadInput, FitnessScoreWithNaNSourceDoesNotAbort)
{
  auto scene = makeScene<pcl::PointXYZ>();
  auto source = pcl::make_shared<CloudXYZ>(*scene);
  (*source)[5].x = std::numeric_limits<float>::quiet_NaN();
  source->is_dense = false;
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
  EXPECT_EQ(phaser.getFitnessScore(),
            std::numeric_limits<double>::max()); // before align
  phaser.setInputSource(source);
  phaser.setInputTarget(scene);
  CloudXYZ out;
  phaser.align(out);
  EXPECT_TRUE(phaser.hasConverged());
  EXPECT_LT(phaser.getFitnessScore(), 0.05);
}

TEST(PhaserRegistration, NullOrEmptyInputsAreRefusedAndDropThePreviousOnes)
{
  const auto target = makeScene<pcl::PointXYZ>();
  const auto source = seenFrom(*target, makePose({0, 0, 1}, 0.4, {0.3, -0.2, 0.0}));
  const auto empty = pcl::make_shared<CloudXYZ>();
  for (int which = 0; which < 4; ++which) {
    pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
    ASSERT_TRUE(alignOnce(phaser, source, target));
    CloudXYZ out;
    if (which == 0)
      phaser.setInputSource(nullptr);
    else if (which == 1)
      phaser.setInputTarget(nullptr);
    else if (which == 2)
      phaser.setInputSource(empty);
    else
      phaser.setInputTarget(empty);
    EXPECT_FALSE(phaser.hasConverged()) << which;
    phaser.align(out); // refused by pcl::Registration::initCompute: no crash
    EXPECT_FALSE(phaser.hasConverged()) << which;
    // The previous clouds are gone: giving the missing one back registers again.
    if (which % 2 == 0)
      phaser.setInputSource(source);
    else
      phaser.setInputTarget(target);
    phaser.align(out);
    EXPECT_TRUE(phaser.hasConverged()) << which;
  }
}
