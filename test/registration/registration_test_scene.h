/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * What the tests of the PCL face share: a synthetic asymmetric scene, poses, the scene
 * seen from a pose, pose errors, and one align.
 */
#pragma once

#include <pcl/common/transforms.h>
#include <pcl/point_types.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <string>

namespace registration_test {

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

inline Eigen::Matrix4f makePose(const Eigen::Vector3d& axis, double angle,
                                const Eigen::Vector3d& t)
{
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  T.topRightCorner<3, 1>() = t;
  return T.cast<float>();
}

inline double rotationErrorDeg(const Eigen::Matrix4f& A, const Eigen::Matrix4f& B)
{
  const Eigen::Matrix3d R =
      (A.topLeftCorner<3, 3>().transpose() * B.topLeftCorner<3, 3>()).cast<double>();
  return Eigen::AngleAxisd(R).angle() / kDeg;
}

inline double translationError(const Eigen::Matrix4f& A, const Eigen::Matrix4f& B)
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

/** Aligns \a source to \a target with the settings of \a phaser (a
 *  pcl::Registration); returns hasConverged(). */
template <typename Registration, typename CloudPtr>
bool alignOnce(Registration& phaser, const CloudPtr& source, const CloudPtr& target)
{
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  typename Registration::PointCloudSource out;
  phaser.align(out);
  return phaser.hasConverged();
}

/** Whether \a text contains \a part (the messages tests' check). */
inline bool has(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

} // namespace registration_test
