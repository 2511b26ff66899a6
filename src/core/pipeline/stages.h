/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: the stages of one estimate in their order (stages.cpp).
#include "pipeline/target_model.h"
#include "priors/allowed_poses.h"
#include "verification/pose_refinement.h"

#include <pcl_phaser/core/result.h>

namespace pcl::phaser::detail {

/** The stages in centered coordinates (source \a points relative to its projection
 *  center) under \a settings and the priors \a allowed: the final pose; everything of
 *  \a result but the caller-frame fields. */
RigidPose estimateCentered(const TargetModel& target, const Eigen::Matrix3Xd& points,
                           const StageSettings& settings, const AllowedPoses& allowed,
                           const ChannelValues& channels, PhaserResult& result);

} // namespace pcl::phaser::detail
