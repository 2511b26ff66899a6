/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "support/error.h"

#include <pcl_phaser/core/parameters.h>

#include <algorithm>
#include <cmath>
#include <omp.h>

namespace pcl::phaser {

std::string validateParameters(const PhaserParameters& p)
{
  if (p.bandwidth < 1 || p.bandwidth > kMaxBandwidth)
    return "bandwidth must be in [1, 256], got " + std::to_string(p.bandwidth);
  if (p.voxel_size == 0.0 && (p.spatial_grid_size < 8 || p.spatial_grid_size > 1024))
    return "spatial grid size must be in [8, 1024], got " +
           std::to_string(p.spatial_grid_size);
  if (!(p.voxel_size >= 0.0) || !std::isfinite(p.voxel_size))
    return "voxel size must be >= 0 (0 = derived from the grid size), got " +
           std::to_string(p.voxel_size);
  if (p.refinement_iterations < 0 || p.refinement_iterations > 10)
    return "refinement iterations must be in [0, 10], got " +
           std::to_string(p.refinement_iterations);
  if (p.rotation_candidates < 1 || p.rotation_candidates > 10)
    return "number of rotation candidates must be in [1, 10], got " +
           std::to_string(p.rotation_candidates);
  if (p.fusion_levels < 1 || p.fusion_levels > 8)
    return "fusion levels must be in [1, 8], got " + std::to_string(p.fusion_levels);
  if (p.passes < 1 || p.passes > 5)
    return "number of passes must be in [1, 5], got " + std::to_string(p.passes);
  if (p.orientation_candidates < 0 || p.orientation_candidates > 20)
    return "number of orientation candidates must be in [0, 20], got " +
           std::to_string(p.orientation_candidates);
  if (p.orientation_bandwidth < 8 || p.orientation_bandwidth > 128)
    return "orientation bandwidth must be in [8, 128], got " +
           std::to_string(p.orientation_bandwidth);
  if (!(p.whitening >= 0.0 && p.whitening <= 1.0))
    return "whitening must be in [0, 1], got " + std::to_string(p.whitening);
  if (!(p.min_inlier_fraction >= 0.0 && p.min_inlier_fraction <= 1.0))
    return "minimum inlier fraction must be in [0, 1], got " +
           std::to_string(p.min_inlier_fraction);
  if (!(p.max_free_space_violation >= 0.0 && p.max_free_space_violation <= 1.0))
    return "maximum free-space violation must be in [0, 1], got " +
           std::to_string(p.max_free_space_violation);
  if (!(p.min_constraint >= 0.0 && p.min_constraint <= 1.0))
    return "minimum constraint must be in [0, 1], got " +
           std::to_string(p.min_constraint);
  if (p.num_threads < 0 || p.num_threads > 64)
    return "number of threads must be in [0, 64] (0: automatic), got " +
           std::to_string(p.num_threads);
  if (!(p.min_peak_score >= 0.0))
    return "the minimum peak score must be >= 0";
  if (!(p.min_normalized_overlap >= 0.0 && p.min_normalized_overlap <= 1.0))
    return "the minimum normalized overlap must be in [0, 1]";
  return {};
}

int resolveThreadCount(int num_threads)
{
  return num_threads > 0 ? num_threads : std::clamp(omp_get_num_procs(), 1, 64);
}

} // namespace pcl::phaser
