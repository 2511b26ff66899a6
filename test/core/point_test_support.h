/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Point-set helpers shared by the tests of verification, the pose refinement and
 * covariance.
 */
#pragma once

#include <Eigen/Core>

#include <random>
#include <vector>

namespace pcl::phaser::test {

/** \a columns as the columns of a 3 x n matrix. */
inline Eigen::Matrix3Xd toMatrix(const std::vector<Eigen::Vector3d>& columns)
{
  Eigen::Matrix3Xd out(3, static_cast<Eigen::Index>(columns.size()));
  for (std::size_t i = 0; i < columns.size(); ++i)
    out.col(static_cast<Eigen::Index>(i)) = columns[i];
  return out;
}

/** \a n points uniform in the cube [-extent, extent]^3, the same for a \a seed. */
inline Eigen::Matrix3Xd randomPoints(int n, double extent, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-extent, extent);
  Eigen::Matrix3Xd p(3, n);
  for (int i = 0; i < n; ++i)
    p.col(i) = Eigen::Vector3d(u(rng), u(rng), u(rng));
  return p;
}

} // namespace pcl::phaser::test
