/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl::phaser {

/** \brief Per-point values of the channels fused with the geometry (intensity,
 *  reflectivity, ambient, luminance...), one vector per channel, in the same order for
 *  target and source. Any scale: each channel is normalized per cloud. */
using ChannelValues = std::vector<Eigen::VectorXd>;

} // namespace pcl::phaser
