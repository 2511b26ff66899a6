/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Point-set helpers shared by the tests of the pose refinement and covariance.
 */
#pragma once

#include <Eigen/Core>

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

} // namespace pcl::phaser::test
