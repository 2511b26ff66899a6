/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "sphere/spherical_harmonics.h"

#include <Eigen/Core>

#include <limits>

namespace pcl::phaser {

/** \brief Result of the sub-grid refinement of a correlation peak. */
struct RefinedRotation {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  double value = 0.0; ///< exact C at \a rotation
  /** \brief The maximized objective at \a rotation: C itself, or C normalized by the
   *  observed energy when supports were given (see refineRotation). */
  double objective = 0.0;
  int iterations = 0;
};

/** \brief Where a spherical signal f was observed: the spectra (B x B) of the indicator
 *  m of the observed cells and of f^2 (zero where unobserved). */
struct SphericalSupport {
  SphericalSpectrum mask;
  SphericalSpectrum energy;
};

/** \brief Newton ascent of C on SO(3) from \a start in the tangent space with exact
 *  evaluation (19-point stencil, step clamped to the grid spacing of
 *  \a output_bandwidth, halved each iteration). With both supports the objective is
 *  C(R) / sqrt(E_f(R) E_h(R)), E_f(R) = <f^2, m_h(R^-1 .)> and E_h(R) = <m_f,
 *  h^2(R^-1 .)>: plain C also rewards overlapping the observed regions, which pulls two
 *  tilted lidars towards equal tilt by about 40 % of their relative tilt.
 *  \param[in] iterations Newton iterations (3 reach < 1e-4 deg on exact data)
 *  \param[in] target_support, source_support both or neither (null: plain C)
 *  \param[in] max_distance radius (radians) of the trust region around \a start
 *  \throws InvalidArgument when only one support is given or max_distance < 0 */
RefinedRotation
refineRotation(const SphericalSpectrum& target, const SphericalSpectrum& source,
               const Eigen::Matrix3d& start, int output_bandwidth, int iterations = 3,
               int num_threads = 1, const SphericalSupport* target_support = nullptr,
               const SphericalSupport* source_support = nullptr,
               double max_distance = std::numeric_limits<double>::infinity());

} // namespace pcl::phaser
