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
  StageSettings settings{params, {}, mode};
  PhaserParameters& p = settings.params;
  p.region.reset();
  p.max_tilt_deg = 0.0;
  if (mode.sensor_centered && !mode.viewpoints && params.voxel_size == 0.0)
    p.spatial_grid_size = std::min(params.spatial_grid_size, kObjectGridSize);
  p.orientation_candidates =
      allowed.orientationCandidates(params.orientation_candidates);
  // The tilt pull it corrects comes from a scanner's band, seen about its origin only.
  p.normalized_refinement = params.normalized_refinement && mode.sensor_centered;
  p.num_threads = resolveThreadCount(params.num_threads);
  settings.limits.min_inlier_fraction = params.min_inlier_fraction;
  settings.limits.min_constraint = params.min_constraint;
  settings.limits.max_free_space_violation = params.max_free_space_violation;
  return settings;
}

} // namespace pcl::phaser::detail
