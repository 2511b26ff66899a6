/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The target model: its spectra, grids, indexes and free space.
 */
#include "channels/surface_orientation.h"
#include "pipeline/cloud_spectra.h"
#include "pipeline/stage_tasks.h"
#include "pipeline/target_model.h"
#include "uncertainty/peak_neighborhood.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace pcl::phaser::detail {
namespace {

/** Verification radius, in coarse voxels. */
constexpr double kVerificationVoxels = 0.5;
/** Radius of the index the local refinement's first step uses: a coarse peak a voxel
 *  off has too few samples (the ground) within kVerificationVoxels. */
constexpr double kReachVoxels = 1.0;
/** Most verification samples of either cloud: an inlier share from this many has a
 *  standard error below 0.004 (a LiDAR scan gives about 3,000). */
constexpr Eigen::Index kMaxVerificationSamples = 16384;

/** The points in the cube holding the inner 75%: densely observed, for the fine grid.
 */
Eigen::Matrix3Xd innerRegion(const Eigen::Matrix3Xd& points)
{
  std::vector<double> r(points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    r[i] = points.col(i).cwiseAbs().maxCoeff();
  std::vector<double> sorted = r;
  const std::size_t k = (sorted.size() * 3) / 4;
  std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    if (r[i] <= sorted[k])
      keep.push_back(i);
  Eigen::Matrix3Xd inner(3, keep.size());
  for (std::size_t i = 0; i < keep.size(); ++i)
    inner.col(i) = points.col(keep[i]);
  return inner;
}

/** \a points thinned (kIndexThinning) and indexed at \a radius with patch normals. */
PointIndex thinnedIndex(const Eigen::Matrix3Xd& points, const SurfacePatches& patches,
                        double radius)
{
  const Eigen::Matrix3Xd thinned = voxelCentroids(points, radius / kIndexThinning);
  return PointIndex(thinned, radius, patchNormalsAt(patches, thinned));
}

/** The target's surface patches and what derives from them (one thread). */
void addSurfaceModel(TargetModel& model, const Eigen::Matrix3Xd& points,
                     double coarse_voxel)
{
  const StageSettings& settings = model.settings;
  const SurfacePatches patches =
      surfacePatches(points, kPatchVoxels * coarse_voxel, Eigen::Vector3d::Zero());
  if (settings.params.orientation_candidates > 0)
    model.orientation =
        orientationSpectrum(patches, settings.params.orientation_bandwidth, 1);
  model.thickness = patches.thickness;
  const double radius = kVerificationVoxels * coarse_voxel;
  model.index = thinnedIndex(points, patches, radius);
  model.reach_index = thinnedIndex(points, patches, kReachVoxels * coarse_voxel);
  model.samples = verificationSamples(points, radius);
  model.sample_weights = orientationWeights(patches, model.samples);
}

/** The fine grid of the later passes: the inner region, little padding (one thread). */
void addFineGrid(TargetModel& model, const Eigen::Matrix3Xd& points,
                 SpatialGridParameters grid)
{
  const Eigen::Matrix3Xd inner = innerRegion(points);
  grid.padding = 0.1;
  grid.min_margin = 2.0 * grid.padding * inner.cwiseAbs().maxCoeff();
  model.fine = occupancySpectrum(makeSpatialGrid(inner, grid), inner, 1);
  model.fine_energy = spectrumEnergy(model.fine);
}

} // namespace

bool sameModel(const StageSettings& prepared, const StageSettings& wanted)
{
  return prepared.params.bandwidth == wanted.params.bandwidth &&
         prepared.params.spatial_grid_size == wanted.params.spatial_grid_size &&
         prepared.params.voxel_size == wanted.params.voxel_size &&
         prepared.params.passes == wanted.params.passes &&
         prepared.params.fusion_levels == wanted.params.fusion_levels &&
         prepared.params.normalized_refinement == wanted.params.normalized_refinement &&
         prepared.params.orientation_candidates ==
             wanted.params.orientation_candidates &&
         prepared.params.orientation_bandwidth == wanted.params.orientation_bandwidth &&
         prepared.mode.sensor_centered == wanted.mode.sensor_centered &&
         prepared.mode.viewpoints == wanted.mode.viewpoints;
}

std::shared_ptr<const TargetModel> prepareTarget(const Eigen::Matrix3Xd& points,
                                                 const StageSettings& settings,
                                                 const ChannelValues& raw_channels)
{
  const auto start = Clock::now();
  const ChannelValues channels = normalizeChannels(raw_channels, points.cols());
  auto model = std::make_shared<TargetModel>();
  model->settings = settings;
  SpatialGridParameters grid;
  grid.grid_size = settings.params.spatial_grid_size;
  grid.voxel_size = settings.params.voxel_size;
  const SpatialGrid coarse = makeSpatialGrid(points, grid);
  // Five one-thread tasks, the longest first: the same result on any thread count.
  runTasks(5, settings.params.num_threads, [&](int part) {
    if (part == 0) {
      addSurfaceModel(*model, points, coarse.voxel_size);
    } else if (part == 1 && settings.params.passes > 1) {
      addFineGrid(*model, points, grid);
    } else if (part == 2) {
      model->coarse = occupancySpectrum(coarse, points, 1);
      model->coarse_energy = spectrumEnergy(model->coarse);
      model->coarse_single = singlePrecision(model->coarse);
    } else if (part == 3 && settings.mode.viewpoints) {
      model->free_space = freeSpace(points, kFreeSpaceBandwidth,
                                    kFreeSpaceMargin * coarse.voxel_size, 1);
    } else if (part == 4) {
      StageTimes unreported;
      model->spherical = sphericalSpectrum(
          points, channels, settings, 1, "target", unreported,
          settings.params.normalized_refinement ? &model->spherical_support : nullptr);
      model->spherical_norm = std::sqrt(spectrumSquaredNorm(model->spherical));
    }
  });
  if (!settings.mode.viewpoints)
    model->magnitude = magnitudeShells(model->coarse, kMagnitudeBandwidth);
  model->preparation_ms = msSince(start);
  return model;
}

Eigen::Matrix3Xd verificationSamples(const Eigen::Matrix3Xd& points, double radius)
{
  Eigen::Matrix3Xd all = voxelCentroids(points, radius);
  if (all.cols() <= kMaxVerificationSamples)
    return all;
  const Eigen::Index step =
      (all.cols() + kMaxVerificationSamples - 1) / kMaxVerificationSamples;
  Eigen::Matrix3Xd kept(3, (all.cols() + step - 1) / step);
  for (Eigen::Index i = 0; i < kept.cols(); ++i)
    kept.col(i) = all.col(i * step);
  return kept;
}

} // namespace pcl::phaser::detail
