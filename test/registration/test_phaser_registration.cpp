/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The pcl::Registration contract of PhaserRegistration on synthetic clouds: known poses
 * recovered, guess, indices, normals, caching, threads, swapped inputs, PCL's kd-tree
 * caching loop, and every bad input of the issue.
 */
#include <pcl_phaser/core/peak_neighborhood.h>
#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <thread>

namespace {

using CloudXYZ = pcl::PointCloud<pcl::PointXYZ>;
constexpr double kDeg = M_PI / 180.0;

/** An asymmetric "yard" around the origin: ground, walls of different lengths, boxes
 * and poles, sampled uniformly on the surfaces (seeded). */
template <typename PointT>
typename pcl::PointCloud<PointT>::Ptr makeScene(unsigned seed = 1, int n = 20000)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto cloud = pcl::make_shared<pcl::PointCloud<PointT>>();
  auto add = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& normal, float value) {
    PointT q;
    q.x = static_cast<float>(p.x());
    q.y = static_cast<float>(p.y());
    q.z = static_cast<float>(p.z());
    if constexpr (pcl::traits::has_normal_v<PointT>) {
      q.normal_x = static_cast<float>(normal.x());
      q.normal_y = static_cast<float>(normal.y());
      q.normal_z = static_cast<float>(normal.z());
    }
    if constexpr (pcl::traits::has_intensity_v<PointT>)
      q.intensity = value;
    cloud->push_back(q);
  };
  for (int i = 0; i < n; ++i) {
    const double a = u(rng), b = u(rng);
    switch (i % 6) {
    case 0: // ground, 40 x 30 m
      add({-18 + 40 * a, -12 + 30 * b, -1.8}, Eigen::Vector3d::UnitZ(), 0.2f);
      break;
    case 1: // long wall at x = 14
      add({14.0, -10 + 22 * a, -1.8 + 6 * b}, -Eigen::Vector3d::UnitX(), 0.6f);
      break;
    case 2: // short wall at y = -9
      add({-6 + 9 * a, -9.0, -1.8 + 4 * b}, Eigen::Vector3d::UnitY(), 0.4f);
      break;
    case 3: { // a box 3 x 2 x 2.5 m at (4, 6)
      const double h = -1.8 + 2.5 * b;
      const double t = 10 * a; // perimeter parameter
      if (t < 3)
        add({3 + t, 5, h}, -Eigen::Vector3d::UnitY(), 0.9f);
      else if (t < 5)
        add({6, 5 + (t - 3), h}, Eigen::Vector3d::UnitX(), 0.9f);
      else if (t < 8)
        add({6 - (t - 5), 7, h}, Eigen::Vector3d::UnitY(), 0.9f);
      else
        add({3, 7 - (t - 8), h}, -Eigen::Vector3d::UnitX(), 0.9f);
      break;
    }
    case 4: { // three poles
      const Eigen::Vector2d c[] = {{-5, 4}, {8, -4}, {-10, -6}};
      const Eigen::Vector2d& p = c[i % 3];
      const double ang = 2 * M_PI * a;
      add({p.x() + 0.2 * std::cos(ang), p.y() + 0.2 * std::sin(ang), -1.8 + 5 * b},
          Eigen::Vector3d(std::cos(ang), std::sin(ang), 0), 1.0f);
      break;
    }
    default: // a slanted roof segment
      add({-12 + 6 * a, 2 + 5 * b, 1.5 + 1.5 * a}, Eigen::Vector3d(-0.24, 0, 0.97),
          0.5f);
    }
  }
  return cloud;
}

Eigen::Matrix4f makePose(const Eigen::Vector3d& axis, double angle,
                         const Eigen::Vector3d& t)
{
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  T.topRightCorner<3, 1>() = t;
  return T.cast<float>();
}

double rotationErrorDeg(const Eigen::Matrix4f& A, const Eigen::Matrix4f& B)
{
  const Eigen::Matrix3d R =
      (A.topLeftCorner<3, 3>().transpose() * B.topLeftCorner<3, 3>()).cast<double>();
  return Eigen::AngleAxisd(R).angle() / kDeg;
}

double translationError(const Eigen::Matrix4f& A, const Eigen::Matrix4f& B)
{
  return (A.topRightCorner<3, 1>() - B.topRightCorner<3, 1>()).norm();
}

/** Source = the scene seen from pose T (source = T^-1 scene): the answer is T. */
template <typename PointT>
typename pcl::PointCloud<PointT>::Ptr seenFrom(const pcl::PointCloud<PointT>& scene,
                                               const Eigen::Matrix4f& T)
{
  auto out = pcl::make_shared<pcl::PointCloud<PointT>>();
  if constexpr (pcl::traits::has_normal_v<PointT>)
    pcl::transformPointCloudWithNormals(scene, *out, Eigen::Matrix4f(T.inverse()));
  else
    pcl::transformPointCloud(scene, *out, Eigen::Matrix4f(T.inverse()));
  return out;
}

} // namespace

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
      // gains on the real scans and the simulated LiDAR pairs: doc/benchmarks.md 6).
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
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  CloudXYZ out;
  phaser.align(out);
  ASSERT_TRUE(phaser.hasConverged());
  const pcl::phaser::PhaserResult e = phaser.getResult();
  EXPECT_TRUE(e.verified);
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

TEST(PhaserRegistration, CovarianceIsPositiveDefiniteAndShrinksWithBandwidth)
{
  // getCovariance() when converged: symmetric positive definite, rotation block at
  // least the model error of the bandwidth, translation block of the size of the
  // error (not of the correlation block), and smaller at a larger bandwidth (paper
  // Fig. 9). Zero when the registration failed.
  const auto target = makeScene<pcl::PointXYZ>(5);
  const Eigen::Matrix4f T = makePose({1, -1, 2}, 1.9, {0.8, -0.6, 0.2});
  double previous_rotation = std::numeric_limits<double>::infinity();
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
    EXPECT_LT((cov - cov.transpose()).norm(), 1e-12 * cov.norm());
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(cov);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0) << "B " << B;
    const double floor = pcl::phaser::rotationModelError(B);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> rot(cov.topLeftCorner<3, 3>());
    EXPECT_GE(rot.eigenvalues().minCoeff(), floor * floor * (1 - 1e-9));
    const double sigma_t = std::sqrt(cov.bottomRightCorner<3, 3>().trace());
    EXPECT_GT(sigma_t, 1e-4);
    EXPECT_LT(sigma_t, 0.2); // the voxel is ~0.4 m; the old eq. 15 block gave ~0.5 m
    const double rotation_trace = cov.topLeftCorner<3, 3>().trace();
    EXPECT_LT(rotation_trace, previous_rotation);
    previous_rotation = rotation_trace;
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
  EXPECT_GT(phaser.getResult().target_ms, 0.0);
  phaser.align(out);
  EXPECT_EQ(phaser.getResult().target_ms, 0.0); // target spectra came from the cache
  EXPECT_TRUE(first == phaser.getFinalTransformation());
  phaser.setInputTarget(target); // invalidates
  phaser.align(out);
  EXPECT_GT(phaser.getResult().target_ms, 0.0);
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
  auto check = [&](auto&& configure) {
    pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
    configure(phaser);
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
    phaser.setInputSource(source);
    phaser.setInputTarget(target);
    CloudXYZ out;
    phaser.align(out);
    ASSERT_TRUE(phaser.hasConverged());
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
