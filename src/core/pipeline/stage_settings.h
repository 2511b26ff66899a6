/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: what the stages of one estimate run with, made once by
// align() and read only.
#include "priors/allowed_poses.h"
#include "verification/ranking.h"

#include <pcl_phaser/core/parameters.h>

namespace pcl::phaser::detail {

/** How align() sees the pair: which free-space tests apply about which centers. */
struct StageMode {
  /** Both clouds are about their sensor origins (ProjectionCenter::SensorOrigin), else
   *  about their centroids. */
  bool sensor_centered = true;
  /** The target's center is where its sensor stood (not an object's frame origin): the
   *  free-space test of source samples applies; else the clouds are objects, and the
   *  magnitude hypotheses join the search. */
  bool viewpoints = true;
  /** So is the source's (with viewpoints): the reverse free-space test applies. */
  bool source_viewpoint = true;
};

/** The settings the stages use, made once per align() by stageSettings() and only read:
 *  the caller's PhaserParameters as this pair runs them, and the mode. A setting a
 * stage reads is read from params; the priors are not there (AllowedPoses holds them).
 */
struct StageSettings {
  /** The caller's settings with the priors removed (no region, max_tilt_deg 0) and four
   *  adjusted: spatial_grid_size capped for objects, orientation_candidates within the
   *  tilt cone, normalized_refinement about sensor origins only, num_threads resolved
   *  (>= 1). */
  PhaserParameters params;
  VerificationLimits limits; ///< of a verified pose, params' limits
  StageMode mode;            ///< which free-space tests apply
};

/** The settings of \a params for a pair registered in \a mode under the priors
 *  \a allowed: the orientation candidates within the tilt cone, the grid of objects
 *  about sensor origins at most kObjectGridSize voxels a side, the normalized
 *  refinement about sensor origins only, and the thread count resolved. */
StageSettings stageSettings(const PhaserParameters& params, const StageMode& mode,
                            const AllowedPoses& allowed);

} // namespace pcl::phaser::detail
