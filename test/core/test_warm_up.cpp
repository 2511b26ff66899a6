/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl::phaser::warmUp(): it changes no result of the aligns around it, with 1 and 2
 * threads and with the memory kept, and refuses bad options.
 */
#include <pcl_phaser/core/warm_up.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <thread>

namespace {

using pcl::phaser::PhaserParameters;
using pcl::phaser::PhaserResult;

/** A source and a target seen in a 12 x 8 x 3 m room with two boxes, with an intensity
 *  channel; the source turned by 20 deg and shifted. */
struct RoomPair {
  Eigen::Matrix3Xd target, source;
  Eigen::VectorXd target_intensity, source_intensity;
};

RoomPair roomPair(int n)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector3d half(6.0, 4.0, 1.5);
  RoomPair pair;
  pair.target.resize(3, n);
  pair.target_intensity.resize(n);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d q(u(rng) * half.x(), u(rng) * half.y(), u(rng) * half.z());
    const int face = i % 8;
    if (face < 6)
      q[face / 2] = (face % 2 ? 1.0 : -1.0) * half[face / 2];
    else
      q = Eigen::Vector3d(face == 6 ? 4.0 : -2.0, face == 6 ? -3.0 : 3.0, -1.0) +
          0.5 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    pair.target.col(i) = q;
    pair.target_intensity[i] = 0.5 + 0.5 * std::sin(2.0 * q.x() + q.z());
  }
  const double yaw = 20.0 * M_PI / 180.0;
  Eigen::Matrix3d R;
  R << std::cos(yaw), -std::sin(yaw), 0, std::sin(yaw), std::cos(yaw), 0, 0, 0, 1;
  // p_target = R p_source + t, so p_source = R^T (p_target - t).
  const Eigen::Vector3d t(0.4, -0.3, 0.1);
  pair.source = R.transpose() * (pair.target.colwise() - t);
  pair.source_intensity = pair.target_intensity;
  return pair;
}

PhaserParameters parameters(int threads)
{
  PhaserParameters p;
  p.bandwidth = 32;
  p.spatial_grid_size = 64;
  p.num_threads = threads;
  return p;
}

PhaserResult alignPair(const RoomPair& pair, const PhaserParameters& p)
{
  const pcl::phaser::Target target(pair.target, {pair.target_intensity});
  const pcl::phaser::SourceCloud source{pair.source, {pair.source_intensity}};
  return pcl::phaser::align(target, source, Eigen::Matrix4d::Identity(), p);
}

void expectIdentical(const PhaserResult& a, const PhaserResult& b)
{
  ASSERT_TRUE(a.error.empty()) << a.error;
  ASSERT_TRUE(b.error.empty()) << b.error;
  EXPECT_TRUE(a.transformation == b.transformation);
  EXPECT_EQ(a.diagnostics.rotation_score, b.diagnostics.rotation_score);
  EXPECT_EQ(a.diagnostics.translation_score, b.diagnostics.translation_score);
  EXPECT_EQ(a.diagnostics.verification.rank, b.diagnostics.verification.rank);
  EXPECT_EQ(a.converged, b.converged);
  const auto& ha = a.diagnostics.hypotheses;
  const auto& hb = b.diagnostics.hypotheses;
  ASSERT_EQ(ha.size(), hb.size());
  for (std::size_t k = 0; k < ha.size(); ++k)
    EXPECT_TRUE(ha[k].transformation == hb[k].transformation);
}

/** Under ctest each test is its own process: the first align below is the first of
 *  the process. */
void checkWarmUpChangesNothing(bool keep_memory)
{
  const RoomPair pair = roomPair(20000);
  for (int threads : {1, 2}) {
    const PhaserResult before = alignPair(pair, parameters(threads));
    pcl::phaser::WarmUpOptions options;
    options.points = 20000;
    options.keep_memory = keep_memory;
    std::string error;
    std::thread warm(
        [&] { error = pcl::phaser::warmUp(parameters(threads), options); });
    warm.join();
    EXPECT_TRUE(error.empty()) << error;
    expectIdentical(before, alignPair(pair, parameters(threads)));
    expectIdentical(before, alignPair(pair, parameters(3 - threads)));
  }
}

TEST(WarmUp, ChangesNoResult)
{
  checkWarmUpChangesNothing(false);
}

TEST(WarmUp, KeepingTheMemoryChangesNoResult)
{
  checkWarmUpChangesNothing(true);
}

TEST(WarmUp, RefusesBadOptions)
{
  pcl::phaser::WarmUpOptions options;
  options.points = 10;
  EXPECT_FALSE(pcl::phaser::warmUp(parameters(1), options).empty());
  options = {};
  options.channels = 9;
  EXPECT_FALSE(pcl::phaser::warmUp(parameters(1), options).empty());
  PhaserParameters bad = parameters(1);
  bad.bandwidth = 0;
  EXPECT_FALSE(pcl::phaser::warmUp(bad, {}).empty());
}

} // namespace
