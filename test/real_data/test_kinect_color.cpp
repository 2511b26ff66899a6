/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * RGB-D: two consecutive Kinect frames of ../shared/data/pcl (organized, with NaNs)
 * under synthetic large transforms, registered as PointXYZRGBA with color fused and
 * with color switched off. Both must succeed; color must change the estimate (the
 * channel really enters); both results are printed, so each run shows the effect of
 * color (no table of doc/benchmarks.md holds it): on these frames geometry alone is
 * not ambiguous.
 */
#include "../registration/test_data.h"
#include "cloud_reading.h"
#include "protocol.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>
#include <pcl/filters/filter.h>
#include <pcl/point_types.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

namespace {

using PointC = pcl::PointXYZRGBA;
using CloudC = pcl::PointCloud<PointC>;

CloudC::Ptr loadFrame(const std::string& relative)
{
  auto cloud = pcl::make_shared<CloudC>();
  std::string error;
  if (!pcl::phaser::loadCloud(pcl::phaser::test::dataPath(relative), *cloud, &error))
    ADD_FAILURE() << error;
  return cloud;
}

TEST(RealRgbd, KinectFramesUnderLargePosesWithAndWithoutColor)
{
  const std::string a = "pcl/frame_20121214T142255.814212.pcd";
  const std::string b = "pcl/frame_20121214T142256.068683.pcd";
  PCL_PHASER_REQUIRE_DATA(a);
  PCL_PHASER_REQUIRE_DATA(b);
  const CloudC::Ptr target = loadFrame(a), second = loadFrame(b);
  ASSERT_FALSE(target->is_dense); // organized, with NaNs: PhaserRegistration skips them
  // The frames were taken ~1 deg / ~1 cm apart (PROVENANCE.md), so the truth of the
  // second frame moved by T^-1 is T up to that: success is judged at 3 deg / 5 cm.
  std::mt19937 rng(11);
  int fused_ok = 0, range_ok = 0;
  const int poses = 5;
  for (int k = 0; k < poses; ++k) {
    const Eigen::Matrix4d T = pcl::phaser::bench::randomPose(rng, 0.5);
    auto source = pcl::make_shared<CloudC>();
    pcl::transformPointCloud(*second, *source, Eigen::Matrix4d(T.inverse()));
    double rre[2], rte[2], rotation_score[2];
    for (int use_color = 1; use_color >= 0; --use_color) {
      pcl::PhaserRegistration<PointC, PointC> phaser;
      phaser.setNumberOfThreads(2);
      phaser.setUseColor(use_color != 0);
      // Centroid: a 57 x 43 deg camera frame moved by T^-1 no longer has its camera at
      // the origin, and the narrow cone turns that offset into strong parallax.
      // ProjectionCenter::Automatic chooses the centroid for these frames too
      // (doc/benchmarks.md, *Automatic projection center*).
      phaser.setProjectionCenter(decltype(phaser)::ProjectionCenter::Centroid);
      phaser.setInputSource(source);
      phaser.setInputTarget(target);
      CloudC aligned;
      phaser.align(aligned);
      const Eigen::Matrix4d G = phaser.getFinalTransformation().cast<double>();
      rotation_score[use_color] = phaser.getResult().diagnostics.rotation_score;
      EXPECT_EQ((phaser.getFusedChannels() & pcl::phaser::CHANNEL_COLOR) != 0u,
                use_color != 0);
      rre[use_color] = pcl::phaser::bench::rreDeg(G, T);
      rte[use_color] = pcl::phaser::bench::rteM(G, T);
      const bool ok =
          phaser.hasConverged() && rre[use_color] < 3.0 && rte[use_color] < 0.05;
      (use_color ? fused_ok : range_ok) += ok;
    }
    // The spectra differ with color; the final pose is polished on the geometry, so
    // both may end on the same pose.
    EXPECT_NE(rotation_score[1], rotation_score[0]) << "color changed nothing";
    std::printf("  pose %d: color fused RRE %.3f deg RTE %.4f m | range only RRE %.3f "
                "deg RTE %.4f m\n",
                k, rre[1], rte[1], rre[0], rte[0]);
  }
  std::printf("  success: color fused %d/%d, range only %d/%d\n", fused_ok, poses,
              range_ok, poses);
  EXPECT_EQ(fused_ok, poses);
  EXPECT_EQ(range_ok, poses);
}

} // namespace
