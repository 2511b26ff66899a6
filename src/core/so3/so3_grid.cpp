/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */

#include "so3/so3_grid.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace pcl::phaser {

Eigen::Matrix3d rotationFromEuler(const EulerZYZ& e)
{
  return (Eigen::AngleAxisd(e.alpha, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(e.beta, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(e.gamma, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

EulerZYZ eulerFromRotation(const Eigen::Matrix3d& R)
{
  EulerZYZ e;
  const double sb = std::hypot(R(0, 2), R(1, 2));
  e.beta = std::atan2(sb, R(2, 2));
  if (sb > 1e-12) {
    e.alpha = std::atan2(R(1, 2), R(0, 2));
    e.gamma = std::atan2(R(2, 1), -R(2, 0));
  } else if (R(2, 2) > 0.0) {
    e.alpha = std::atan2(R(1, 0), R(0, 0));
  } else {
    e.alpha = std::atan2(-R(1, 0), -R(0, 0));
  }
  return e;
}

EulerZYZ gridEuler(const So3GridIndex& i, int output_bandwidth)
{
  const double bo = output_bandwidth;
  return {M_PI * i.alpha / bo, M_PI * (2 * i.beta + 1) / (4.0 * bo),
          M_PI * i.gamma / bo};
}

double rotationDistance(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B)
{
  // Via the quaternion (2 atan2), accurate for tiny angles, unlike acos of the trace.
  return Eigen::AngleAxisd(Eigen::Matrix3d(A.transpose() * B)).angle();
}

} // namespace pcl::phaser
