/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "verification/pose_refinement.h"

#include <Eigen/Core>

namespace pcl::phaser {

/** \brief Fewest matched samples (with a target normal) fitCovariance needs: fewer
 * leave the six directions of a pose too thinly measured to estimate their spread. */
constexpr int kMinFitSamples = 30;

/** \brief Edge of the blocks of fitCovariance, in coarse voxels: the point-to-plane
 *  residuals of neighboring samples are correlated (0.23 between adjacent samples, 0.02
 *  at 2-3 coarse voxels, none beyond 4 on the revisit pairs of lidar/balm_handheld,
 *  doc/benchmarks.md "Covariance calibration on revisits"), so samples closer than
 *  this are not independent evidence. */
constexpr double kFitBlockVoxels = 4.0;

/** \brief Factor by which fitCovariance scales the spread the residuals show, for the
 *  error they cannot show: the pose absorbs the part of a systematic error (ranging
 *  bias, beam divergence, the sampling of each scan) that a rigid motion explains and
 *  leaves only the rest in the residuals. Fitted once (the value at which the mean 6-D
 *  NEES is 6) on 304 converged revisit pairs derived from the poses of
 *  lidar/balm_handheld, with the odometry's drift removed from their reference; the 35
 *  pairs of its pairs.txt were held out (doc/benchmarks.md "Covariance calibration on
 *  revisits"). */
constexpr double kFitModelErrorFactor = 7.3;

/** \brief Covariance of \a pose from its own geometric evidence: the point-to-plane fit
 *  of \a samples against \a target that refinePose climbs (the same matches, weights
 *  and residuals). With H = sum w J J^T and the residual terms g_i = w_i r_i J_i
 *  (J_i = [q_i x n_i; n_i], q_i the moved sample, n_i its target normal), it is the
 *  cluster-robust sandwich H^-1 M H^-1, M = sum over blocks of edge \a block of (sum
 *  of the block's g_i)(...)^T, averaged over two grids offset by half a block,
 *  scaled by kFitModelErrorFactor, plus d d^T for the Gauss-Newton step d = -H^-1 sum
 *  g_i that would still move \a pose to the fit's optimum.
 *  The error is omega = Log(R_true R^T) [rad], then nu = t_true - Exp(omega) t [m]
 *  (a perturbation q -> Exp(omega) q + nu of the moved samples, about the origin of
 *  the target frame). Deterministic (serial sums in sample and block order).
 *  \param[in] target target points with normals \param[in] samples source samples
 *  with weights and normals \param[in] pose the pose \param[in] block meters, > 0
 *  \param[out] covariance 6 x 6, symmetric positive definite when true is returned
 *  \return false (\a covariance untouched) with fewer than kMinFitSamples matches or
 *  when the evidence leaves a direction unmeasured (the result would not be positive
 *  definite) */
bool fitCovariance(const PointIndex& target, const VerificationSamples& samples,
                   const RigidPose& pose, double block,
                   Eigen::Matrix<double, 6, 6>& covariance);

} // namespace pcl::phaser
