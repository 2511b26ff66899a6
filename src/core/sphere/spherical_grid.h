/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl::phaser {

/** \brief Driscoll-Healy sampling of the sphere at bandwidth B (2B x 2B cells): ring j
 *  has colatitude theta_j = pi (2j+1) / (4B), column k azimuth phi_k = pi k / B.
 *  Samples are stored row-major, one row per ring: f[j * 2B + k]. The poles are never
 *  sampled. */

/** \brief Colatitude of ring j. */
double ringColatitude(int ring, int bandwidth);

/** \brief Azimuth of column k. */
double columnAzimuth(int column, int bandwidth);

/** \brief Driscoll-Healy quadrature weights w_j, j = 0..2B-1 (sum 2, symmetric).
 *  With them, int g dw = (pi/B) sum_j w_j sum_k g(theta_j, phi_k) is exact for every g
 *  of degree < 2B. */
std::vector<double> quadratureWeights(int bandwidth);

/** \brief Unit direction of a grid sample: (sin t cos p, sin t sin p, cos t). */
Eigen::Vector3d sampleDirection(int ring, int column, int bandwidth);

/** \brief Index j * 2B + k of the cell that contains the direction of \a p (which need
 * not be normalized). Returns -1 for the zero vector or non-finite input. */
int cellIndex(const Eigen::Vector3d& p, int bandwidth);

} // namespace pcl::phaser
