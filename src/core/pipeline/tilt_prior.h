/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// The gravity prior (PhaserParameters::max_tilt_deg): which rotations are searched and
// the guard that no result outside it is returned.
#include "pipeline/pipeline_internal.h"

namespace pcl::phaser {
namespace detail {

/** \brief Tilt of \a R in radians: the angle between R z and z (Euler beta), [0, pi].
 */
double tiltOf(const Eigen::Matrix3d& R);

/** \brief Beta rows of a (2 Bo)^3 SO(3) grid the prior of \a params searches
 *  (betaRowsForTilt); 0, the whole grid, when the prior is off. */
int tiltPriorRows(const PhaserParameters& params, int output_bandwidth);

/** \brief \a params with, when the prior is on, fewer rotation hypotheses (those the
 *  cone leaves are fewer and more often right). */
StageParameters withTiltPrior(const StageParameters& params);

/** \brief Whether \a R keeps within the prior of \a params, with half a grid cell
 *  (pi / (2 B)) for the refinements' drift; always true when the prior is off. */
bool withinTiltPrior(const PhaserParameters& params, const Eigen::Matrix3d& R);

/** \brief When the prior is on and \a pose is tilted beyond it: \a pose becomes the
 *  best-ranked hypothesis of \a result within it (or, when none is, \a pose with its
 *  tilt clamped), and the result is no longer verified, so it does not converge. */
void keepWithinTiltPrior(const PhaserParameters& params, RigidPose& pose,
                         PhaserResult& result);

} // namespace detail
} // namespace pcl::phaser
