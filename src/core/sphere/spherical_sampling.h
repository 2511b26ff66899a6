/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl::phaser {

/** \brief A cloud seen as a function on the sphere, on the Driscoll-Healy grid. */
struct SphericalSamples {
  int bandwidth = 0;
  std::vector<double> values; ///< 4B^2 samples, row-major, one row per ring
  int observed_cells = 0;     ///< cells that received at least one point
};

/** \brief The Driscoll-Healy cell (cellIndex) of every point of \a points (3 x n,
 *  relative to the projection center) at \a bandwidth; independent of \a num_threads.
 */
std::vector<int> sphereCells(const Eigen::Matrix3Xd& points, int bandwidth,
                             int num_threads = 1);

/** \brief Bins one value per point into the cells of sphereCells: each observed cell
 *  takes the mean of its points' values, less the mean over the observed cells;
 *  unobserved cells (outside the field of view, shadows) stay zero. Points with cell -1
 *  and non-finite values are skipped. */
SphericalSamples binOnSphere(const std::vector<int>& cells,
                             const Eigen::VectorXd& values, int bandwidth);

} // namespace pcl::phaser
