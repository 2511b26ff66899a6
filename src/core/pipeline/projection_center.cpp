/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "pipeline/projection_center.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace pcl::phaser {

namespace {

/** The distance of the nearest of \a points (a strided subset of at most 20,000) to
 *  \a viewpoint and the bounding-box diagonal of that subset; infinity without finite
 *  points. */
std::pair<double, double> nearestAndDiagonal(const Eigen::Matrix3Xd& points,
                                             const Eigen::Vector3d& viewpoint)
{
  constexpr Eigen::Index kMaxChecked = 20000;
  const Eigen::Index step = std::max<Eigen::Index>(1, points.cols() / kMaxChecked);
  double nearest = std::numeric_limits<double>::infinity();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(nearest), hi = -lo;
  for (Eigen::Index i = 0; i < points.cols(); i += step) {
    if (!points.col(i).allFinite())
      continue;
    nearest = std::min(nearest, (points.col(i) - viewpoint).norm());
    lo = lo.cwiseMin(points.col(i));
    hi = hi.cwiseMax(points.col(i));
  }
  return {nearest, std::isfinite(nearest) ? (hi - lo).norm() : nearest};
}

} // namespace

bool looksSensorCentered(const Eigen::Matrix3Xd& points,
                         const Eigen::Vector3d& viewpoint)
{
  const auto [nearest, diagonal] = nearestAndDiagonal(points, viewpoint);
  return std::isfinite(nearest) && nearest <= kSensorFrameNearestShare * diagonal;
}

bool originOnData(const Eigen::Matrix3Xd& points, const Eigen::Vector3d& viewpoint)
{
  const auto [nearest, diagonal] = nearestAndDiagonal(points, viewpoint);
  return std::isfinite(nearest) &&
         nearest <= std::max(kOnDataDistance, kOnDataDiagonalShare * diagonal);
}

} // namespace pcl::phaser
