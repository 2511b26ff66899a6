/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: the target model's preparation and the stages of one
// estimate in their order (estimate.cpp).
#include "pipeline/stage_state.h"

namespace pcl::phaser::detail {

/** Prepares a target whose points are relative to its projection center. */
std::shared_ptr<const TargetModel> prepareTarget(const Eigen::Matrix3Xd& points,
                                                 const StageParameters& params,
                                                 const ChannelValues& channels);
/** The stages in centered coordinates (source points relative to its projection
 *  center): the final pose; everything of \a result but the caller-frame fields. */
RigidPose estimateCentered(const TargetModel& target, const Eigen::Matrix3Xd& points,
                           const StageParameters& params, const ChannelValues& channels,
                           PhaserResult& result);

} // namespace pcl::phaser::detail
