/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <Eigen/Core>

#include <vector>

namespace pcl::phaser {

/** \brief Per-point values of the channels fused with the geometry, one vector per
 *  channel, in the same order for target and source; any scale. */
using ChannelValues = std::vector<Eigen::VectorXd>;

} // namespace pcl::phaser
