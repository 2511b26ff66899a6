/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "pipeline/stage_settings.h"

#include <algorithm>

namespace pcl::phaser::detail {
namespace {

/** Most voxels a side of the translation grid of clouds not seen from their center
 *  (objects): the polish, not the grid, pins their translation, and 128 voxels put
 *  several grid cells between a bunny view's points (the bunny pairs: as right at 64,
 *  2.4x faster). */
constexpr int kObjectGridSize = 64;

} // namespace

StageSettings stageSettings(const PhaserParameters& params, const StageMode& mode,
                            const AllowedPoses& allowed)
{
  StageSettings settings;
  settings.bandwidth = params.bandwidth;
  settings.fusion_levels = params.fusion_levels;
  settings.spatial_grid_size =
      mode.sensor_centered && !mode.viewpoints && params.voxel_size == 0.0
          ? std::min(params.spatial_grid_size, kObjectGridSize)
          : params.spatial_grid_size;
  settings.voxel_size = params.voxel_size;
  settings.passes = params.passes;
  settings.rotation_candidates = params.rotation_candidates;
  settings.orientation_candidates =
      allowed.orientationCandidates(params.orientation_candidates);
  settings.orientation_bandwidth = params.orientation_bandwidth;
  settings.refinement_iterations = params.refinement_iterations;
  settings.whitening = params.whitening;
  // The tilt pull it corrects comes from a scanner's band, seen about its origin only.
  settings.normalized_refinement = params.normalized_refinement && mode.sensor_centered;
  settings.limits.min_inlier_fraction = params.min_inlier_fraction;
  settings.limits.min_constraint = params.min_constraint;
  settings.limits.max_free_space_violation = params.max_free_space_violation;
  settings.num_threads = resolveThreadCount(params.num_threads);
  settings.mode = mode;
  return settings;
}

} // namespace pcl::phaser::detail
