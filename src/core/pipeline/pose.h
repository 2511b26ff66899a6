/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: a pose of the search, how the stages verify it and refine it
// on the verification samples.
#include "pipeline/source_context.h"
#include "so3/so3_correlation_grid.h"
#include "verification/pose_refinement.h"

#include <pcl_phaser/core/result.h>

#include <cmath>
#include <memory>

namespace pcl::phaser::detail {

/** Rotation peaks closer than this are one hypothesis (a few grid cells at B = 64). */
constexpr double kHypothesisSeparation = 10.0 * M_PI / 180.0;

struct Viewpoint; ///< the source seen from a pose (passes.h)

/** A pose (centered coordinates), how it verifies, the last accepted pass's grid. */
struct Pose : RigidPose {
  Verification verification;
  std::shared_ptr<const So3CorrelationGrid> grid;
  So3GridIndex peak{};
  bool verifiable = false; ///< hypotheses and passes are ranked by verification
  std::shared_ptr<const Viewpoint> view; ///< what a refused pass measured from here
};

/** Whether \a next replaces \a current (by rank when verifiable). */
bool improves(const Pose& next, const Pose& current);

/** verifyBothWays of \a pose on \a num_threads threads; its time into \a times. */
Verification verificationOf(const SourceContext& source, const RigidPose& pose,
                            StageTimes& times, int num_threads);

/** \a pose refined on the verification samples (refineOnSamples: within the
 *  hypothesis separation and two coarse voxels; on all samples when \a all_samples,
 *  else the polish's), kept when it ranks higher. */
Pose refinedOnSamples(const SourceContext& source, const Pose& pose, StageTimes& times,
                      int num_threads, bool all_samples = false);

} // namespace pcl::phaser::detail
