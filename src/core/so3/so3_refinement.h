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

/** \brief Where a spherical signal f was observed and where its energy lies: the
 *  spectra (B x B, like the signal's) of the indicator m of the observed cells and of
 *  f^2 (the squared de-meaned signal, zero where unobserved). */
struct SphericalSupport {
  SphericalSpectrum mask;
  SphericalSpectrum energy;
};

/** \brief Newton ascent of C on SO(3) in the tangent space with exact evaluation
 *  (19-point stencil, step clamped to the grid spacing, halved each iteration);
 *  pole-safe and coordinate-free (doc/so3-correlation-spec.md section 5).
 *
 * With the supports of both signals the objective is the energy-normalized
 * correlation C(R) / sqrt(E_f(R) E_h(R)), where E_f(R) = <f^2, m_h(R^-1 .)> is the
 * energy of the target over the rotated source's observed region and E_h(R) =
 * <m_f, h^2(R^-1 .)> that of the source over the target's. Unobserved cells are zero,
 * so plain C also rewards overlapping the two observed regions where the signals are
 * strong: two LiDARs tilted against each other have tilted field-of-view bands whose
 * edges (the near ground, far below the mean range) pull C towards equal tilt by about
 * 40 % of the relative tilt. The normalization divides that reward out. The three
 * correlations share one Wigner recurrence (evaluateCorrelations).
 *  \param[in] target, source spectra (B x B) as given to So3Correlator
 *  \param[in] start a grid peak
 *  \param[in] output_bandwidth Bo of the grid the start came from (sets the step)
 *  \param[in] iterations Newton iterations (3 reach < 1e-4 deg on exact data)
 *  \param[in] num_threads worker threads
 *  \param[in] target_support, source_support supports of the two signals (both or
 *  neither); null: plain C
 *  \param[in] max_distance radius (radians) of the trust region around \a start: a
 *  step that would leave it ends on its boundary
 *  \throws InvalidArgument when only one support is given or max_distance < 0 */
RefinedRotation
refineRotation(const SphericalSpectrum& target, const SphericalSpectrum& source,
               const Eigen::Matrix3d& start, int output_bandwidth, int iterations = 3,
               int num_threads = 1, const SphericalSupport* target_support = nullptr,
               const SphericalSupport* source_support = nullptr,
               double max_distance = std::numeric_limits<double>::infinity());

} // namespace pcl::phaser
