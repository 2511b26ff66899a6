/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: the final refinement of the pose (final_pose.cpp).
#include "pipeline/pose.h"

#include <pcl_phaser/core/result.h>

namespace pcl::phaser::detail {

/** The final rotation refinement (not when \a decided) and shift (kept when they verify
 *  better) and the local refinement on all samples; scores, translation covariance and
 *  rotation samples into \a result. */
Pose refineFinalPose(const SourceContext& source, Pose pose, bool decided,
                     PhaserResult& result);

} // namespace pcl::phaser::detail
