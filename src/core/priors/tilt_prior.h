/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: how the gravity prior (PhaserParameters::max_tilt_deg)
// restricts the search; allowed_poses.h guards the answer.
#include <pcl_phaser/core/parameters.h>

#include <Eigen/Core>

namespace pcl::phaser::detail {

/** \brief Whether \a params set a gravity prior: 0 < max_tilt_deg < 180 (at 180 every
 *  rotation is within it). */
bool tiltPriorOn(const PhaserParameters& params);

/** \brief Tilt of \a R in radians: the angle between R z and z (Euler beta), [0, pi].
 */
double tiltOf(const Eigen::Matrix3d& R);

/** \brief Beta rows of a (2 Bo)^3 SO(3) grid the prior of \a params searches
 *  (betaRowsForTilt); 0, the whole grid, when the prior is off. */
int tiltPriorRows(const PhaserParameters& params, int output_bandwidth);

/** \brief The orientation candidates searched under the prior of \a params: fewer
 *  (those the cone leaves are fewer and more often right); all when it is off. */
int tiltPriorOrientationCandidates(const PhaserParameters& params);

} // namespace pcl::phaser::detail
