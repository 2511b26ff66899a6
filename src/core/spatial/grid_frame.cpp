/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "spatial/grid_frame.h"

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace pcl::phaser {
namespace detail {
namespace {

/** Most points the yaw search reads (every k-th of a larger cloud). */
constexpr Eigen::Index kMaxYawPoints = 20000;
/** A yaw is kept only when it shrinks the box by more than this share. */
constexpr double kMinGain = 0.01;

/** Area of the (x, y) box of \a xy turned by \a yaw (radians). */
double boxArea(const Eigen::Matrix2Xd& xy, double yaw)
{
  const double c = std::cos(yaw), s = std::sin(yaw);
  Eigen::Array2d lo = Eigen::Array2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Array2d hi = -lo;
  for (Eigen::Index i = 0; i < xy.cols(); ++i) {
    const Eigen::Array2d p(c * xy(0, i) - s * xy(1, i), s * xy(0, i) + c * xy(1, i));
    lo = lo.min(p);
    hi = hi.max(p);
  }
  return (hi - lo).prod();
}

/** The yaw of least boxArea among center + k step, |k| <= count. */
double bestYaw(const Eigen::Matrix2Xd& xy, double center, double step, int count)
{
  double best = center, least = boxArea(xy, center);
  for (int k = -count; k <= count; ++k) {
    const double area = boxArea(xy, center + k * step);
    if (area < least) {
      least = area;
      best = center + k * step;
    }
  }
  return best;
}

} // namespace

Eigen::Matrix3d gridAlignedYaw(const Eigen::Matrix3Xd& points)
{
  const Eigen::Index n = points.cols();
  if (n < 3)
    return Eigen::Matrix3d::Identity();
  const Eigen::Index stride = (n + kMaxYawPoints - 1) / kMaxYawPoints;
  Eigen::Matrix2Xd xy(2, (n + stride - 1) / stride);
  for (Eigen::Index i = 0; i < xy.cols(); ++i)
    xy.col(i) = points.col(i * stride).head<2>();
  const double degree = M_PI / 180.0;
  double yaw = bestYaw(xy, 45.0 * degree, 0.5 * degree, 90);
  yaw = bestYaw(xy, yaw, 0.01 * degree, 50);
  if (!(boxArea(xy, yaw) < (1.0 - kMinGain) * boxArea(xy, 0.0)))
    return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

} // namespace detail
} // namespace pcl::phaser
