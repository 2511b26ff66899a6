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

/** \brief The Driscoll-Healy cell of every point (-1 for the center and non-finite
 *  points), computed once and shared by all channels of a cloud.
 *  \param[in] points 3 x n, relative to the projection center
 *  \param[in] bandwidth B (1..256)
 *  \param[in] num_threads worker threads; the result does not depend on it */
std::vector<int> sphereCells(const Eigen::Matrix3Xd& points, int bandwidth,
                             int num_threads = 1);

/** \brief Bins per-point values into the 2B x 2B Driscoll-Healy cells given by
 *  sphereCells: each observed cell takes the mean of its points' values; the mean over
 *  the observed cells is then subtracted and unobserved cells stay at zero, so the
 *  polar caps outside a LiDAR's vertical field of view and the shadows inject no signal
 *  (the reference implementation smeared the nearest ring over them). Points with cell
 *  -1 (the center, non-finite points) are skipped.
 *  \param[in] cells from sphereCells
 *  \param[in] values one per point
 *  \param[in] bandwidth B of the cells */
SphericalSamples binOnSphere(const std::vector<int>& cells,
                             const Eigen::VectorXd& values, int bandwidth);

} // namespace pcl::phaser
