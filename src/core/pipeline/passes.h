/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: the later passes, each from the last pose's viewpoint
// (passes.cpp).
#include "pipeline/pose.h"
#include "so3/so3_refinement.h"

#include <memory>

namespace pcl::phaser::detail {

/** The source seen from a pose: spectrum, support, residual grid and its peak. */
struct Viewpoint {
  SphericalSpectrum H;
  SphericalSupport support; ///< with the normalized refinement
  std::shared_ptr<const So3CorrelationGrid> grid;
  So3GridIndex peak{};
};

/** The source seen from \a pose (its spectrum, and support with the normalized
 *  refinement). */
std::shared_ptr<Viewpoint> viewFrom(const SourceContext& source, const RigidPose& pose,
                                    StageTimes& times);

/** The residual grid of \a H against the target (rows within a 20 deg tilt) and its
 *  peak (for a verifiable pose, within a cell or two: the one near the identity) into
 *  \a pose. */
void residualGrid(const SourceContext& source, const SphericalSpectrum& H, Pose& pose,
                  StageTimes& times);

/** Later passes from \a pose's viewpoint, kept while they verify better; the passes
 *  kept so far into \a passes. */
Pose reprojectionPasses(const SourceContext& source, Pose pose, int& passes,
                        StageTimes& times);

} // namespace pcl::phaser::detail
