/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: whether a pose stands out, and the verdict on the final pose
// (verdict.cpp).
#include "pipeline/pose.h"

#include <pcl_phaser/core/result.h>

#include <limits>
#include <vector>

namespace pcl::phaser::detail {

/** How the pose compared with the best hypothesis distinct from it. */
struct Distinctness {
  bool stands_out = true; ///< true when no hypothesis is distinct
  double runner_up_rank = -std::numeric_limits<double>::infinity();
  double error = 0.0; ///< standard error of the rank difference (sensor origins)
};

/** Whether \a pose outranks the best hypothesis distinct from it by more than
 *  kDistinctErrors standard errors of the difference. */
Distinctness standsOut(const SourceContext& source, const Pose& pose,
                       const std::vector<Hypothesis>& hypotheses);
/** The final \a pose's verification, runner-up, fit covariance and verdict into
 *  \a result (against its hypotheses). */
void judgeFinalPose(const SourceContext& source, const Pose& pose,
                    PhaserResult& result);

} // namespace pcl::phaser::detail
