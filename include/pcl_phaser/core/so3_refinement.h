/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/core/spherical_harmonics.h>

#include <Eigen/Core>

namespace pcl_phaser {

/** \brief Result of the sub-grid refinement of a correlation peak. */
struct RefinedRotation {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  double value = 0.0; ///< exact C at \a rotation
  int iterations = 0;
};

/** \brief Newton ascent of C on SO(3) in the tangent space with exact evaluation
 *  (19-point stencil, step clamped to the grid spacing, halved each iteration);
 * pole-safe and coordinate-free (doc/so3-correlation-spec.md section 5). \param[in]
 * target, source spectra (B x B) as given to So3Correlator \param[in] start a grid peak
 *  \param[in] output_bandwidth Bo of the grid the start came from (sets the step)
 *  \param[in] iterations Newton iterations (3 reach < 1e-4 deg on exact data)
 *  \param[in] num_threads worker threads */
RefinedRotation refineRotation(const SphericalSpectrum& target,
                               const SphericalSpectrum& source,
                               const Eigen::Matrix3d& start, int output_bandwidth,
                               int iterations = 3, int num_threads = 1);

} // namespace pcl_phaser
