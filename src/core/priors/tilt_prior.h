/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: how the gravity prior (PhaserParameters::max_tilt_deg)
// restricts the search; AllowedPoses (allowed_poses.h) asks these for its tilt cone.
#include <pcl_phaser/core/parameters.h>

#include <Eigen/Core>

namespace pcl::phaser::detail {

/** \brief Whether \a params set a gravity prior: 0 < max_tilt_deg < 180 (at 180 every
 *  rotation is within it). */
bool tiltPriorOn(const PhaserParameters& params);

/** \brief Tilt of \a R in radians: the angle between R z and z (Euler beta), [0, pi].
 */
double tiltOf(const Eigen::Matrix3d& R);

/** \brief The orientation candidates searched of \a candidates within the tilt cone of
 *  \a max_tilt radians: fewer (those the cone leaves are fewer and more often right),
 *  never fewer than the share of rotations the cone holds. */
int tiltConeOrientationCandidates(double max_tilt, int candidates);

} // namespace pcl::phaser::detail
