/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "verification/pose_refinement.h"

#include <Eigen/Core>

namespace pcl::phaser {

/** \brief Fewest matched samples (with a target normal) fitCovariance needs to
 *  estimate the spread of all six pose directions. */
constexpr int kMinFitSamples = 30;

/** \brief Edge of the blocks of fitCovariance, in coarse voxels: point-to-plane
 *  residuals measured on lidar revisit pairs were correlated up to 2-3 coarse voxels
 *  apart and not beyond 4. */
constexpr double kFitBlockVoxels = 4.0;

/** \brief Factor on the spread the residuals show, for the systematic error a rigid
 *  motion absorbs (ranging bias, beam divergence, sampling). Calibrated on loop
 *  triangles, which need no reference (pcl_phaser_batch triangles): on 303 triangles
 *  of 173 handheld loop edges 7.3 gave a mean NEES of 2.4 and 100 % within the 95 %
 *  bound, 3.65 gives 4.9 and 96.7 % (the parity halves: 5.4-5.7, 91-95 %). The 7.3 fitted
 *  against the dataset's poses absorbed their own 0.2 m drift. */
constexpr double kFitModelErrorFactor = 3.65;

/** \brief Covariance of \a pose from the point-to-plane fit of \a samples against
 *  \a target that refinePose climbs (same matches, weights and residuals): with H =
 *  sum w J J^T and g_i = w_i r_i J_i (J_i = [q_i x n_i; n_i]), the cluster-robust
 *  sandwich kFitModelErrorFactor H^-1 M H^-1, M = sum over blocks of edge \a block
 *  (meters) of (sum of their g_i)(...)^T averaged over two grids offset by half a
 *  block, plus d d^T for the Gauss-Newton step d = -H^-1 sum g_i still open. The error
 *  is omega = Log(R_true R^T) [rad], then nu = t_true - Exp(omega) t [m].
 *  Deterministic, the same for any \a num_threads (the look-ups' threads,
 *  forEachPlaneMatch). \return false (\a covariance untouched) with fewer than
 *  kMinFitSamples matches or when a direction is unmeasured (not positive definite) */
bool fitCovariance(const PointIndex& target, const VerificationSamples& samples,
                   const RigidPose& pose, double block,
                   Eigen::Matrix<double, 6, 6>& covariance, int num_threads = 1);

} // namespace pcl::phaser
