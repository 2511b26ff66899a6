/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "pipeline/projection_center.h"
#include "sphere/spherical_grid.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace pcl::phaser {

double viewCoverage(const Eigen::Matrix3Xd& points, const Eigen::Vector3d& viewpoint)
{
  constexpr int kBandwidth = 8;
  const int side = 2 * kBandwidth;
  std::vector<int> hits(static_cast<std::size_t>(side) * side, 0);
  Eigen::Index seen = 0;
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const int cell = cellIndex(points.col(i) - viewpoint, kBandwidth);
    if (cell < 0)
      continue;
    ++hits[static_cast<std::size_t>(cell)];
    ++seen;
  }
  if (seen == 0)
    return 0.0;
  // Stray returns (a person walking by a depth camera) must not count.
  const double needed = std::max(1.0, 1e-3 * static_cast<double>(seen));
  // Ring j spans colatitudes [j, j+1] pi / 2B: each cell (cos lower - cos upper) / 4B.
  double covered = 0.0;
  for (int ring = 0; ring < side; ++ring) {
    const double area =
        0.5 * (std::cos(M_PI * ring / side) - std::cos(M_PI * (ring + 1) / side)) /
        side;
    for (int column = 0; column < side; ++column)
      if (hits[static_cast<std::size_t>(ring) * side + column] >= needed)
        covered += area;
  }
  return covered;
}

double polarFraction(const Eigen::Matrix3Xd& points, const Eigen::Vector3d& viewpoint)
{
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  std::vector<Eigen::Vector3d> directions;
  directions.reserve(static_cast<std::size_t>(points.cols()));
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const Eigen::Vector3d d = points.col(i) - viewpoint;
    const double norm = d.norm();
    if (!(norm > 0.0) || !std::isfinite(norm))
      continue;
    directions.push_back(d / norm);
    scatter += directions.back() * directions.back().transpose();
  }
  if (directions.empty())
    return 0.0;
  const Eigen::Vector3d axis =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(0);
  const double cos45 = std::sqrt(0.5);
  std::size_t polar = 0;
  for (const Eigen::Vector3d& d : directions)
    polar += std::abs(d.dot(axis)) > cos45;
  return static_cast<double>(polar) / static_cast<double>(directions.size());
}

bool looksSensorCentered(const Eigen::Matrix3Xd& points,
                         const Eigen::Vector3d& viewpoint)
{
  return viewCoverage(points, viewpoint) >= kSensorFrameCoverage &&
         polarFraction(points, viewpoint) <= kSensorFramePolarFraction;
}

bool originOnData(const Eigen::Matrix3Xd& points, const Eigen::Vector3d& viewpoint)
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
  if (!std::isfinite(nearest))
    return false;
  return nearest <= std::max(kOnDataDistance, kOnDataDiagonalShare * (hi - lo).norm());
}

} // namespace pcl::phaser
