/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The pcl::Registration contract of PhaserRegistration on synthetic clouds: known poses
 * recovered, guess, indices, normals, caching, threads, swapped inputs, PCL's kd-tree
 * caching loop (bad inputs: test_phaser_registration_bad_input.cpp).
 */
#include "registration_test_scene.h"
#include "uncertainty/peak_neighborhood.h"

#include <pcl_phaser/lazy_kdtree.h>
#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <thread>

using namespace registration_test;

TEST(PhaserRegistration, RecoversKnownPoseSensorOrigin)
{
  const auto target = makeScene<pcl::PointXYZ>();
  for (const Eigen::Matrix4f& T : {makePose({0, 0, 1}, 2.3, {1.2, -0.7, 0.1}),
                                   makePose({1, 2, 3}, -1.4, {-0.4, 1.5, 0.3}),
                                   makePose({0.3, -1, 0.2}, 0.9, {0.0, 0.0, 0.0})})
    for (bool normalized : {false, true}) {
      pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
      pcl::phaser::PhaserParameters params = phaser.getParameters();
      params.normalized_refinement = normalized;
      phaser.setParameters(params);
      phaser.setInputSource(seenFrom(*target, T));
      phaser.setInputTarget(target);
      CloudXYZ out;
      phaser.align(out);
      ASSERT_TRUE(phaser.hasConverged());
      // On this small synthetic room the normalized refinement costs up to 0.3 deg (it
      // gains on the real scans and the simulated LiDAR pairs).
      EXPECT_LT(rotationErrorDeg(phaser.getFinalTransformation(), T),
                normalized ? 0.75 : 0.5);
      EXPECT_LT(translationError(phaser.getFinalTransformation(), T), 0.05);
      EXPECT_EQ(out.size(), target->size());
      EXPECT_LT(phaser.getFitnessScore(), 0.05);
    }
}

TEST(PhaserRegistration, ConvergenceMeansAVerifiedPose)
{
  const auto target = makeScene<pcl::PointXYZ>();
  const auto source = seenFrom(*target, makePose({0, 0, 1}, 2.3, {1.2, -0.7, 0.1}));
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
  ASSERT_TRUE(alignOnce(phaser, source, target));
  CloudXYZ out;
  EXPECT_TRUE(phaser.getResult().diagnostics.verified);
  const pcl::phaser::Verification e = phaser.getResult().diagnostics.verification;
  EXPECT_GT(e.inlier_fraction, 0.5); // the same room seen again
  EXPECT_GT(e.constraint, 0.05);     // floor and walls of two directions
  EXPECT_LE(e.free_space_violation,
            pcl::phaser::PhaserParameters().max_free_space_violation);
  // Each threshold flips the decision where the pose's own figure lies.
  const auto convergesWith = [&](auto set) {
    pcl::phaser::PhaserParameters p = phaser.getParameters();
    set(p);
    phaser.setParameters(p);
    phaser.align(out);
    return phaser.hasConverged();
  };
  const pcl::phaser::PhaserParameters defaults = phaser.getParameters();
  EXPECT_TRUE(
      convergesWith([&](auto& p) { p.min_inlier_fraction = e.inlier_fraction; }));
  EXPECT_FALSE(convergesWith(
      [&](auto& p) { p.min_inlier_fraction = e.inlier_fraction + 1e-3; }));
  phaser.setParameters(defaults);
  EXPECT_TRUE(convergesWith([&](auto& p) { p.min_constraint = e.constraint; }));
  EXPECT_FALSE(convergesWith([&](auto& p) { p.min_constraint = e.constraint + 1e-3; }));
  phaser.setParameters(defaults);
  EXPECT_TRUE(convergesWith(
      [&](auto& p) { p.max_free_space_violation = e.free_space_violation; }));
  if (e.free_space_violation > 0.0) {
    EXPECT_FALSE(convergesWith(
        [&](auto& p) { p.max_free_space_violation = 0.99 * e.free_space_violation; }));
  }
  // An unrelated room does not verify.
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> unrelated;
  unrelated.setInputSource(makeScene<pcl::PointXYZ>(6, 300));
  unrelated.setInputTarget(target);
  unrelated.align(out);
  EXPECT_FALSE(unrelated.hasConverged());
}

TEST(PhaserRegistration, DegenerateInputsDoNotConverge)
{
  const auto target = makeScene<pcl::PointXYZ>();
  const auto cloudOf = [](std::initializer_list<Eigen::Vector3f> points) {
    auto c = pcl::make_shared<CloudXYZ>();
    for (const Eigen::Vector3f& p : points)
      c->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    return c;
  };
  const auto two = cloudOf({{1, 0, 0}, {0, 2, 0}});
  const auto collinear = cloudOf({{1, 0, 0}, {2, 0, 0}, {3, 0, 0}});
  const auto three = cloudOf({{1, 0, 0}, {0, 2, 0}, {0, 0, 3}});
  const std::vector<std::pair<CloudXYZ::Ptr, CloudXYZ::Ptr>> cases = {
      {two, target}, {collinear, target}, {target, three}, {three, three}};
  for (const auto& [src, tgt] : cases) {
    pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
    phaser.setInputSource(src);
    phaser.setInputTarget(tgt);
    CloudXYZ out;
    phaser.align(out);
    EXPECT_FALSE(phaser.hasConverged()) << src->size() << " -> " << tgt->size();
  }
}

TEST(PhaserRegistration, VolumetricNoiseIsVerifiedOnBoundedSamples)
{
  // 30,000 points uniform in a 10 x 10 x 1 m box, seen from a pose 0.5 m and 30 deg
  // away: no surface, and one verification sample per occupied cell of the radius,
  // about 28,000 of them, more than the engine keeps (16,384: kMaxVerificationSamples);
  // every other one is kept. Converged or not, converged means right.
  auto noise = pcl::make_shared<CloudXYZ>();
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  for (int i = 0; i < 30000; ++i)
    noise->push_back(pcl::PointXYZ(u(rng), u(rng), 0.1f * u(rng)));
  const Eigen::Matrix4f T = makePose({0, 0, 1}, M_PI / 6, {0.4f, 0.3f, 0.0f});
  auto source = pcl::make_shared<CloudXYZ>();
  pcl::transformPointCloud(*noise, *source, Eigen::Matrix4f(T.inverse()));
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
  phaser.setNumberOfThreads(2);
  phaser.setInputSource(source);
  phaser.setInputTarget(noise);
  CloudXYZ out;
  phaser.align(out);
  const pcl::phaser::PhaserResult& r = phaser.getResult();
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_GT(r.diagnostics.verification_samples, 8000);
  EXPECT_LE(r.diagnostics.verification_samples, 16384);
  if (phaser.hasConverged()) {
    const Eigen::Matrix4f G = phaser.getFinalTransformation();
    const Eigen::AngleAxisf d(
        Eigen::Matrix3f(G.topLeftCorner<3, 3>().transpose() * T.topLeftCorner<3, 3>()));
    EXPECT_LT(d.angle(), 2.0f * static_cast<float>(M_PI) / 180.0f);
    EXPECT_LT((G.topRightCorner<3, 1>() - T.topRightCorner<3, 1>()).norm(), 0.3f);
  }
}

TEST(PhaserRegistration, CentroidModeHandlesLargeOffsets)
{
  // PCL's SAC-IA pattern: the source moved by 100 m and yawed by 90 degrees.
  const auto target = makeScene<pcl::PointXYZ>(3);
  const Eigen::Matrix4f T = makePose({0, 0, 1}, M_PI / 2, {100, 0, 0});
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
  phaser.setProjectionCenter(decltype(phaser)::ProjectionCenter::Centroid);
  phaser.setInputSource(seenFrom(*target, T));
  phaser.setInputTarget(target);
  CloudXYZ out;
  phaser.align(out);
  ASSERT_TRUE(phaser.hasConverged());
  EXPECT_LT(rotationErrorDeg(phaser.getFinalTransformation(), T), 1.0);
  EXPECT_LT(translationError(phaser.getFinalTransformation(), T), 0.2);
}

TEST(PhaserRegistration, SwappedInputsGiveTheInverse)
{
  const auto target = makeScene<pcl::PointXYZ>(5);
  const Eigen::Matrix4f T = makePose({1, -1, 4}, 2.0, {0.8, 0.4, -0.2});
  const auto source = seenFrom(*target, T);
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> forward, backward;
  CloudXYZ out;
  forward.setInputSource(source);
  forward.setInputTarget(target);
  forward.align(out);
  backward.setInputSource(target);
  backward.setInputTarget(source);
  backward.align(out);
  ASSERT_TRUE(forward.hasConverged() && backward.hasConverged());
  const Eigen::Matrix4f inverse = backward.getFinalTransformation().inverse();
  EXPECT_LT(rotationErrorDeg(forward.getFinalTransformation(), inverse), 1.0);
  EXPECT_LT(translationError(forward.getFinalTransformation(), inverse), 0.2);
  EXPECT_GT(rotationErrorDeg(backward.getFinalTransformation(), T), 10.0);
}

TEST(PhaserRegistration, GuessIsAppliedAndComposed)
{
  const auto target = makeScene<pcl::PointXYZ>(7);
  const Eigen::Matrix4f T = makePose({0, 0, 1}, 1.0, {0.5, 0.5, 0});
  const Eigen::Matrix4f guess = makePose({0, 0, 1}, 0.8, {0.3, 0.2, 0});
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
  phaser.setInputSource(seenFrom(*target, T));
  phaser.setInputTarget(target);
  CloudXYZ out;
  phaser.align(out, guess);
  ASSERT_TRUE(phaser.hasConverged());
  EXPECT_LT(rotationErrorDeg(phaser.getFinalTransformation(), T), 1.0);
  EXPECT_LT(translationError(phaser.getFinalTransformation(), T), 0.2);
}

TEST(PhaserRegistration, IndicesSelectTheEstimateOutputIsWholeCloud)
{
  const auto target = makeScene<pcl::PointXYZ>(9);
  const Eigen::Matrix4f T = makePose({0, 1, 1}, 0.7, {0.3, -0.2, 0.1});
  auto source = seenFrom(*target, T);
  // Append garbage far away; indices exclude it, so the estimate is unaffected.
  const std::size_t n = source->size();
  for (int i = 0; i < 2000; ++i)
    source->push_back(pcl::PointXYZ(500.0f + i, -300.0f, 40.0f));
  auto indices = pcl::make_shared<pcl::Indices>(n);
  for (std::size_t i = 0; i < n; ++i)
    (*indices)[i] = static_cast<int>(i);
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
  phaser.setInputSource(source);
  phaser.setIndices(indices);
  phaser.setInputTarget(target);
  CloudXYZ out;
  phaser.align(out);
  ASSERT_TRUE(phaser.hasConverged());
  EXPECT_LT(rotationErrorDeg(phaser.getFinalTransformation(), T), 1.0);
  EXPECT_EQ(out.size(), source->size());
}

TEST(PhaserRegistration, NormalsAreRotatedAndInputUntouched)
{
  const auto target = makeScene<pcl::PointNormal>(11);
  const Eigen::Matrix4f T = makePose({2, 1, 1}, -1.1, {0.4, 0.1, 0.0});
  const auto source = seenFrom(*target, T);
  const pcl::PointCloud<pcl::PointNormal> source_copy = *source;
  pcl::PhaserRegistration<pcl::PointNormal, pcl::PointNormal> phaser;
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  pcl::PointCloud<pcl::PointNormal> out;
  phaser.align(out);
  ASSERT_TRUE(phaser.hasConverged());
  EXPECT_LT(rotationErrorDeg(phaser.getFinalTransformation(), T), 1.0);
  double worst = 0.0;
  for (std::size_t i = 0; i < out.size(); ++i)
    worst = std::max<double>(
        worst,
        (out[i].getNormalVector3fMap() - (*target)[i].getNormalVector3fMap()).norm());
  EXPECT_LT(worst, 0.03); // 1 degree ~ 0.017
  for (std::size_t i = 0; i < source->size(); ++i)
    ASSERT_EQ(0, std::memcmp(&(*source)[i], &source_copy[i], sizeof(pcl::PointNormal)));
}

TEST(PhaserRegistration, CovarianceIsPositiveDefiniteAndCoversTheError)
{
  // getCovariance() when converged: the covariance of the final pose's own fit
  // (PhaserResult::fit_covariance), symmetric positive definite, its translation block
  // of the size of the error (not of the correlation block), and the error of the pose
  // inside its 99.9 % ellipsoid (chi-square, 6 dof: 22.46). Zero when the registration
  // failed.
  const auto target = makeScene<pcl::PointXYZ>(5);
  const Eigen::Matrix4f T = makePose({1, -1, 2}, 1.9, {0.8, -0.6, 0.2});
  for (int B : {32, 64}) {
    pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
    phaser.setBandwidth(B);
    phaser.setInputSource(seenFrom(*target, T));
    phaser.setInputTarget(target);
    CloudXYZ out;
    phaser.align(out);
    ASSERT_TRUE(phaser.hasConverged()) << "B " << B;
    const Eigen::Matrix<double, 6, 6> cov = phaser.getCovariance();
    ASSERT_TRUE(cov.allFinite());
    EXPECT_TRUE(cov.isApprox(phaser.getResult().fit_covariance)) << "B " << B;
    // The engine finishes its answer: align()'s covariance is poseCovariance's.
    const pcl::phaser::PhaserResult& result = phaser.getResult();
    EXPECT_EQ(result.covariance,
              pcl::phaser::poseCovariance(result,
                                          pcl::phaser::rotationUncertainty(result), B));
    EXPECT_LT((cov - cov.transpose()).norm(), 1e-12 * cov.norm());
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(cov);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0) << "B " << B;
    const double sigma_t = std::sqrt(cov.bottomRightCorner<3, 3>().trace());
    EXPECT_GT(sigma_t, 1e-4);
    EXPECT_LT(sigma_t, 0.2); // the voxel is ~0.4 m; the old eq. 15 block gave ~0.5 m
    const Eigen::Matrix4d estimate = phaser.getFinalTransformation().cast<double>();
    const Eigen::Matrix4d truth = T.cast<double>();
    const Eigen::AngleAxisd omega(Eigen::Matrix3d(
        truth.topLeftCorner<3, 3>() * estimate.topLeftCorner<3, 3>().transpose()));
    Eigen::Matrix<double, 6, 1> e;
    e << omega.angle() * omega.axis(),
        truth.topRightCorner<3, 1>() - estimate.topRightCorner<3, 1>();
    const double nees = e.dot(cov.ldlt().solve(e));
    std::printf("  B %d: NEES %.2f\n", B, nees);
    EXPECT_LT(nees, 22.46) << "B " << B;
  }
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> unrelated;
  unrelated.setInputSource(makeScene<pcl::PointXYZ>(6, 300));
  unrelated.setInputTarget(target);
  pcl::phaser::PhaserParameters never = unrelated.getParameters();
  never.min_peak_score = 1e9; // nothing converges
  unrelated.setParameters(never);
  CloudXYZ out;
  unrelated.align(out);
  ASSERT_FALSE(unrelated.hasConverged());
  EXPECT_TRUE(unrelated.getCovariance().isZero());
  EXPECT_TRUE(unrelated.getResult().covariance.isZero());
}

TEST(PhaserRegistration, CachedTargetGivesIdenticalResults)
{
  const auto target = makeScene<pcl::PointXYZ>(13);
  const Eigen::Matrix4f T = makePose({0, 0, 1}, -2.5, {1.0, 0.0, 0.0});
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
  phaser.setInputSource(seenFrom(*target, T));
  phaser.setInputTarget(target);
  CloudXYZ out;
  phaser.align(out);
  const Eigen::Matrix4f first = phaser.getFinalTransformation();
  EXPECT_GT(phaser.getResult().diagnostics.times.target, 0.0);
  phaser.align(out);
  EXPECT_EQ(phaser.getResult().diagnostics.times.target,
            0.0); // target spectra came from the cache
  EXPECT_TRUE(first == phaser.getFinalTransformation());
  phaser.setInputTarget(target); // invalidates
  phaser.align(out);
  EXPECT_GT(phaser.getResult().diagnostics.times.target, 0.0);
  EXPECT_TRUE(first == phaser.getFinalTransformation());
}

TEST(PhaserRegistration, ThreadCountDoesNotChangeTheResult)
{
  const auto target = makeScene<pcl::PointXYZ>(15);
  const auto source = seenFrom(*target, makePose({1, 0, 1}, 1.9, {-0.5, 0.3, 0.0}));
  Eigen::Matrix4f results[3];
  for (int k = 0; k < 3; ++k) {
    pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
    if (k == 0) {
      EXPECT_EQ(phaser.getNumberOfThreads(), 0u); // automatic by default
    }
    phaser.setNumberOfThreads(k); // 0: one per hardware thread
    phaser.setInputSource(source);
    phaser.setInputTarget(target);
    CloudXYZ out;
    phaser.align(out);
    results[k] = phaser.getFinalTransformation();
  }
  EXPECT_TRUE(results[0] == results[1]);
  EXPECT_TRUE(results[1] == results[2]);
}

TEST(PhaserRegistration, TwoRegistrationsAtOnce)
{
  const auto target = makeScene<pcl::PointXYZ>(17);
  const Eigen::Matrix4f T[2] = {makePose({0, 0, 1}, 0.6, {0.2, 0.1, 0}),
                                makePose({1, 1, 0}, -2.2, {-0.3, 0.6, 0.1})};
  Eigen::Matrix4f got[2];
  std::thread workers[2];
  for (int k = 0; k < 2; ++k)
    workers[k] = std::thread([&, k] {
      pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
      phaser.setBandwidth(k == 0 ? 48 : 64); // different plans built concurrently too
      phaser.setInputSource(seenFrom(*target, T[k]));
      phaser.setInputTarget(target);
      CloudXYZ out;
      phaser.align(out);
      got[k] = phaser.getFinalTransformation();
    });
  for (auto& w : workers)
    w.join();
  for (int k = 0; k < 2; ++k)
    EXPECT_LT(rotationErrorDeg(got[k], T[k]), 1.5);
}

TEST(PhaserRegistration, PclKdTreeCachingSchemes)
{
  // The loop of PCL's test_sac_ia: every combination of provided / forced search trees.
  const auto target = makeScene<pcl::PointXYZ>(19);
  const Eigen::Matrix4f T = makePose({0, 0, 1}, M_PI / 2, {0.5, 0.5, 0});
  const auto source = seenFrom(*target, T);
  for (int scheme = 0; scheme < 4; ++scheme) {
    pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
    const bool force_target = scheme & 1, force_source = scheme & 2;
    auto tree = pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
    tree->setInputCloud(target);
    phaser.setSearchMethodTarget(tree, force_target);
    auto tree_source = pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
    tree_source->setInputCloud(source);
    phaser.setSearchMethodSource(tree_source, force_source);
    phaser.setInputSource(source);
    phaser.setInputTarget(target);
    CloudXYZ out;
    phaser.align(out);
    ASSERT_TRUE(phaser.hasConverged()) << "scheme " << scheme;
    EXPECT_LT(rotationErrorDeg(phaser.getFinalTransformation(), T), 1.0);
    EXPECT_LT(phaser.getFitnessScore(), 0.05) << "scheme " << scheme;
    EXPECT_EQ(out.size(), source->size());
  }
}

TEST(PhaserRegistration, ChannelsFollowThePointType)
{
  using namespace pcl::phaser;
  using XYZ = pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ>;
  using XYZI = pcl::PhaserRegistration<pcl::PointXYZI, pcl::PointXYZI>;
  using RGB = pcl::PhaserRegistration<pcl::PointXYZRGB, pcl::PointXYZRGB>;
  using Normal = pcl::PhaserRegistration<pcl::PointNormal, pcl::PointNormal>;
  EXPECT_EQ(XYZ().getFusedChannels(), static_cast<std::uint32_t>(CHANNEL_RANGE));
  EXPECT_EQ(XYZI().getFusedChannels(),
            static_cast<std::uint32_t>(CHANNEL_RANGE | CHANNEL_INTENSITY));
  EXPECT_EQ(RGB().getFusedChannels(),
            static_cast<std::uint32_t>(CHANNEL_RANGE | CHANNEL_COLOR));
  // PointNormal's curvature is not intensity (PCL's IntensityFieldAccessor would say
  // so).
  EXPECT_EQ(Normal().getFusedChannels(), static_cast<std::uint32_t>(CHANNEL_RANGE));
  pcl::PhaserRegistration<pcl::PointXYZI, pcl::PointXYZI> off;
  off.setUseIntensity(false);
  EXPECT_EQ(off.getFusedChannels(), static_cast<std::uint32_t>(CHANNEL_RANGE));
  EXPECT_FALSE(off.getParameters().channels & CHANNEL_INTENSITY);
}

TEST(PhaserRegistration, AllPointTypesInstantiated)
{
  auto run = [](auto tag) {
    using PointT = decltype(tag);
    const auto target = makeScene<PointT>(21, 3000);
    const Eigen::Matrix4f T = makePose({0, 0, 1}, 1.2, {0.3, 0.0, 0.0});
    pcl::PhaserRegistration<PointT, PointT> phaser;
    phaser.setInputSource(seenFrom(*target, T));
    phaser.setInputTarget(target);
    pcl::PointCloud<PointT> out;
    phaser.align(out);
    EXPECT_TRUE(phaser.hasConverged());
    EXPECT_LT(rotationErrorDeg(phaser.getFinalTransformation(), T), 1.5);
  };
  run(pcl::PointXYZ());
  run(pcl::PointXYZI());
  run(pcl::PointXYZRGB());
  run(pcl::PointXYZRGBA());
  run(pcl::PointNormal());
  run(pcl::PointXYZINormal());
}

// The target's search tree builds its index at the first search (LazyKdTree): it then
// answers like PCL's kd-tree, also after a new cloud, and pcl::Registration's own
// getFitnessScore (not virtual: called through a base reference) finds it built.
TEST(PhaserRegistration, LazyTargetTreeSearchesLikePclsKdTree)
{
  const auto a = makeScene<pcl::PointXYZ>(23);
  const auto b = seenFrom(*a, makePose({0, 0, 1}, 0.4, {0.3, -0.2, 0.1}));
  pcl::phaser::LazyKdTree<pcl::PointXYZ> lazy;
  pcl::search::KdTree<pcl::PointXYZ> eager;
  for (const auto& cloud : {a, b}) {
    lazy.setInputCloud(cloud);
    eager.setInputCloud(cloud);
    for (std::size_t i = 0; i < a->size(); i += 97) {
      pcl::Indices li, ei;
      std::vector<float> ld, ed;
      ASSERT_EQ(lazy.nearestKSearch((*a)[i], 3, li, ld),
                eager.nearestKSearch((*a)[i], 3, ei, ed));
      EXPECT_EQ(li, ei);
      EXPECT_EQ(ld, ed);
      ASSERT_EQ(lazy.radiusSearch((*a)[i], 0.3, li, ld),
                eager.radiusSearch((*a)[i], 0.3, ei, ed));
      EXPECT_EQ(li, ei);
    }
  }

  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
  ASSERT_TRUE(alignOnce(phaser, b, a));
  pcl::Registration<pcl::PointXYZ, pcl::PointXYZ>& base = phaser;
  EXPECT_LT(base.getFitnessScore(), 0.05);
  EXPECT_DOUBLE_EQ(base.getFitnessScore(), phaser.getFitnessScore());
}
