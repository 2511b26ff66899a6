/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "pipeline/cloud_spectra.h"
#include "support/error.h"

#include <string>

namespace pcl::phaser::detail {
namespace {

/** Binary occupancy: the near-sensor density must not vote for stacking the sensors. */
constexpr double kOccupancySaturation = 0.05;

} // namespace

SphericalSpectrum sphericalSpectrum(const Eigen::Matrix3Xd& points,
                                    const ChannelValues& channels,
                                    const StageSettings& settings, int num_threads,
                                    const char* which, StageTimes& times,
                                    SphericalSupport* support)
{
  int observed = 0;
  SphericalSpectrum F = cloudSphericalSpectrum(
      points, channels, settings.params.bandwidth, settings.params.fusion_levels,
      num_threads, observed, times.sampling, times.sht, support);
  if (observed < 2)
    throw InvalidArgument(
        std::string(which) +
        " cloud has fewer than two distinct directions from its "
        "projection center (empty, all at the center, or a single point)");
  if (!(spectrumSquaredNorm(F) > 0.0))
    throw InvalidArgument(std::string(which) + " cloud is constant on the sphere");
  return F;
}

SpatialSpectrum occupancySpectrum(const SpatialGrid& grid,
                                  const Eigen::Matrix3Xd& points, int num_threads)
{
  SpatialVoxelParameters voxel;
  voxel.saturation = kOccupancySaturation;
  voxel.num_threads = num_threads;
  return computeSpectrum(voxelize(grid, points, voxel), num_threads);
}

SpatialSpectrumF occupancySpectrumSingle(const SpatialGrid& grid,
                                         const Eigen::Matrix3Xd& points,
                                         int num_threads)
{
  SpatialVoxelParameters voxel;
  voxel.saturation = kOccupancySaturation;
  voxel.num_threads = num_threads;
  return computeSpectrum(voxelizeSingle(grid, points, voxel), num_threads);
}

} // namespace pcl::phaser::detail
