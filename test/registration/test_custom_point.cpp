/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * A point type that libpcl_phaser does not instantiate (an Ouster-style driver point),
 * registered through the opt-in header <pcl_phaser/custom_point_types.h>.
 */
#define PCL_NO_PRECOMPILE
#include <pcl_phaser/custom_point_types.h>

#include <pcl/common/transforms.h>
#include <pcl/point_types.h>
#include <pcl/register_point_struct.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace test_types {
struct EIGEN_ALIGN16 OusterPoint {
  PCL_ADD_POINT4D;
  float intensity;
  std::uint32_t t;
  std::uint16_t reflectivity;
  std::uint16_t ring;
  std::uint16_t ambient;
  std::uint32_t range;
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};
} // namespace test_types

// clang-format off
POINT_CLOUD_REGISTER_POINT_STRUCT(test_types::OusterPoint,
                                  (float, x, x)(float, y, y)(float, z, z)
                                  (float, intensity, intensity)(std::uint32_t, t, t)
                                  (std::uint16_t, reflectivity, reflectivity)
                                  (std::uint16_t, ring, ring)(std::uint16_t, ambient, ambient)
                                  (std::uint32_t, range, range))
// clang-format on

namespace {

/** A room of 20,000 Ouster-style points: floor and three walls, every field set. */
pcl::PointCloud<test_types::OusterPoint>::Ptr ousterRoom()
{
  using PointT = test_types::OusterPoint;
  auto target = pcl::make_shared<pcl::PointCloud<PointT>>();
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 20000; ++i) {
    PointT p{};
    const float a = u(rng), b = u(rng);
    switch (i % 4) {
    case 0:
      p.x = -15 + 30 * a;
      p.y = -10 + 20 * b;
      p.z = -1.5f;
      break;
    case 1:
      p.x = 12.0f;
      p.y = -8 + 16 * a;
      p.z = -1.5f + 5 * b;
      break;
    case 2:
      p.x = -10 + 8 * a;
      p.y = -9.0f;
      p.z = -1.5f + 3 * b;
      break;
    default:
      p.x = 3 + 3 * a;
      p.y = 5.0f;
      p.z = -1.5f + 2 * b;
    }
    p.intensity = 100.0f * a;
    p.reflectivity = static_cast<std::uint16_t>(40000 * b); // raw uint16 scale
    p.ambient = static_cast<std::uint16_t>(300 + 100 * a);
    p.range = static_cast<std::uint32_t>(1000.0f * std::sqrt(p.x * p.x + p.y * p.y));
    target->push_back(p);
  }
  return target;
}

} // namespace

TEST(PhaserRegistrationCustomPoint, OusterStylePointAligns)
{
  using PointT = test_types::OusterPoint;
  const auto target = ousterRoom();
  Eigen::Matrix4f T = Eigen::Matrix4f::Identity();
  T.topLeftCorner<3, 3>() = Eigen::AngleAxisf(-2.2f, Eigen::Vector3f::UnitZ()).matrix();
  T.topRightCorner<3, 1>() = Eigen::Vector3f(0.6f, 0.3f, 0.0f);
  auto source = pcl::make_shared<pcl::PointCloud<PointT>>();
  pcl::transformPointCloud(*target, *source, Eigen::Matrix4f(T.inverse()));

  pcl::PhaserRegistration<PointT, PointT> phaser;
  // The traits see all four channels of the driver type (range from xyz, never
  // `range`).
  EXPECT_EQ(phaser.getFusedChannels(),
            static_cast<std::uint32_t>(
                pcl::phaser::CHANNEL_RANGE | pcl::phaser::CHANNEL_INTENSITY |
                pcl::phaser::CHANNEL_REFLECTIVITY | pcl::phaser::CHANNEL_AMBIENT));
  phaser.setUseAmbient(false);
  EXPECT_FALSE(phaser.getFusedChannels() & pcl::phaser::CHANNEL_AMBIENT);
  phaser.setUseAmbient(true);
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  pcl::PointCloud<PointT> out;
  phaser.align(out);
  ASSERT_TRUE(phaser.hasConverged());
  const Eigen::Matrix4f G = phaser.getFinalTransformation();
  EXPECT_LT(Eigen::AngleAxisf(Eigen::Matrix3f(G.topLeftCorner<3, 3>().transpose() *
                                              T.topLeftCorner<3, 3>()))
                .angle(),
            0.5f * static_cast<float>(M_PI) / 180.0f);
  EXPECT_LT((G.topRightCorner<3, 1>() - T.topRightCorner<3, 1>()).norm(), 0.05f);
  // Other fields travel with the points.
  EXPECT_EQ(out[10].range, (*source)[10].range);
  EXPECT_EQ(out[10].intensity, (*source)[10].intensity);
  EXPECT_LT(phaser.getFitnessScore(), 0.01);
}
