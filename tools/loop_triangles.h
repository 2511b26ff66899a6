/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * A check of the loop edges' covariances that needs no reference poses: around every
 * triangle of converged edges the composed estimates should close, and the closure's
 * NEES under the propagated covariances should follow chi-square(6).
 */
#pragma once

#include "batch_records.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace pcl {
namespace phaser {
namespace batch {

/** \brief The closure of edges a -> b, b -> c and a -> c (a < b < c; each measured with
 *  the earlier scan as target): r = (Log(R_ab R_bc R_ac^T), R_ab t_bc + t_ab - t_ac),
 *  in getCovariance()'s convention (omega = Log(R_true R^T), nu = t_true - t, target
 *  frame), and its NEES under the first-order sum of the three covariances. */
struct Closure {
  int a = 0, b = 0, c = 0;
  Eigen::Matrix<double, 6, 1> residual = Eigen::Matrix<double, 6, 1>::Zero();
  double nees = 0.0, nees_rotation = 0.0, nees_translation = 0.0;
};

/** \brief Every triangle of converged records, in (a, b, c) order. */
std::vector<Closure> loopClosures(const std::vector<Record>& records);

/** \brief A summary of \a closures: how many, the share within the 95 % bounds of
 *  chi-square(6) (12.59) and, per block, chi-square(3) (7.81), the mean NEES (6 when
 *  calibrated), the median closure angle (deg) and distance (m). */
std::string closureSummary(const std::vector<Closure>& closures);

/** \brief The 95 % bound of chi-square with 6 and with 3 degrees of freedom. */
constexpr double kChiSquare6Bound95 = 12.5916;
constexpr double kChiSquare3Bound95 = 7.81473;

} // namespace batch
} // namespace phaser
} // namespace pcl
