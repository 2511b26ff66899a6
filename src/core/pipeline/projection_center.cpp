/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "pipeline/projection_center.h"
#include "sphere/spherical_sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

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

double hiddenShare(const Eigen::Matrix3Xd& cloud, const Eigen::Vector3d& viewpoint)
{
  constexpr int kBandwidth = 256;
  constexpr double kRangeShare = 0.05, kDiagonalShare = 0.01;
  if (cloud.cols() == 0)
    return 0.0;
  const Eigen::Matrix3Xd points = cloud.colwise() - viewpoint;
  const double margin =
      kDiagonalShare *
      (points.rowwise().maxCoeff() - points.rowwise().minCoeff()).norm();
  const std::vector<int> cells = sphereCells(points, kBandwidth);
  std::vector<double> nearest(4 * static_cast<std::size_t>(kBandwidth) * kBandwidth,
                              std::numeric_limits<double>::infinity());
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    if (cells[static_cast<std::size_t>(i)] >= 0) {
      double& seen =
          nearest[static_cast<std::size_t>(cells[static_cast<std::size_t>(i)])];
      seen = std::min(seen, points.col(i).norm());
    }
  Eigen::Index hidden = 0, counted = 0;
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const int c = cells[static_cast<std::size_t>(i)];
    if (c < 0)
      continue;
    const double front = nearest[static_cast<std::size_t>(c)];
    ++counted;
    hidden += points.col(i).norm() > front * (1.0 + kRangeShare) + margin ? 1 : 0;
  }
  return counted > 0 ? static_cast<double>(hidden) / static_cast<double>(counted) : 0.0;
}

} // namespace pcl::phaser
