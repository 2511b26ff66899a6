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

/** The settings the stages use: the PhaserParameters of the same names as the mode
 *  and the priors adjust them, and the mode. stageSettings() sets every field (the
 *  defaults here are placeholders); the stages only read them. */
struct StageSettings {
  int bandwidth = 0;              ///< B of the spherical spectra and the SO(3) grid
  int fusion_levels = 0;          ///< of the spherical signals
  int spatial_grid_size = 0;      ///< voxels a side of the coarse grid (see voxel_size)
  double voxel_size = 0.0;        ///< meters; 0: from spatial_grid_size
  int passes = 1;                 ///< most passes, >= 1
  int rotation_candidates = 1;    ///< peaks of the range correlation
  int orientation_candidates = 0; ///< orientation-histogram peaks, within the tilt cone
  int orientation_bandwidth = 0;  ///< B of the orientation histograms
  int refinement_iterations = 0;  ///< Newton steps of the rotation refinement
  double whitening = 0.0;         ///< of the pass-1 translation correlation, [0, 1]
  bool normalized_refinement = false; ///< about sensor origins only
  VerificationLimits limits;          ///< of a verified pose
  int num_threads = 1;                ///< resolved, >= 1
  StageMode mode;                     ///< which free-space tests apply
};

/** The settings of \a params for a pair registered in \a mode under the priors
 *  \a allowed: the orientation candidates within the tilt cone, the grid of objects
 *  about sensor origins at most kObjectGridSize voxels a side, the normalized
 *  refinement about sensor origins only, and the thread count resolved. */
StageSettings stageSettings(const PhaserParameters& params, const StageMode& mode,
                            const AllowedPoses& allowed);

} // namespace pcl::phaser::detail
