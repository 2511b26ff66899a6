/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The yaw that turns a cloud's horizontal extent onto the axes of the translation grid.
 */
#pragma once

#include <Eigen/Core>

namespace pcl::phaser {
namespace detail {

/** \brief The rotation about z that gives \a points their smallest axis-aligned box in
 *  (x, y): the box of the rotated points has the least area over yaws in [0, 90) deg,
 *  searched in 0.5 deg steps on at most 20,000 evenly strided points, then to 0.01 deg.
 *  The translation grid follows the axes of the frame it is built in; a map in a frame
 *  turned against its streets (a site frame) fills a larger box with empty voxels (35
 *  deg of yaw: 2.9x the voxels of its own frame). z is kept, so gravity priors hold.
 *  Identity for fewer than 3 points or when no yaw shrinks the box by 1 %.
 *  Deterministic. */
Eigen::Matrix3d gridAlignedYaw(const Eigen::Matrix3Xd& points);

} // namespace detail
} // namespace pcl::phaser
