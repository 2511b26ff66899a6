/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: what the stages use of the target, prepared once per target
// and settings (the Target's cache keeps the last).
#include "channels/spectral_magnitude.h"
#include "index/point_index.h"
#include "pipeline/stage_settings.h"
#include "so3/so3_refinement.h"
#include "spatial/spatial_correlation.h"
#include "spatial/spatial_single.h"
#include "sphere/spherical_harmonics.h"
#include "verification/verification.h"

#include <Eigen/Core>

#include <memory>

namespace pcl::phaser::detail {

/** Patches of the orientation histograms and the sample weights, in coarse voxels. */
constexpr double kPatchVoxels = 1.0;
/** Direction cells of the free-space test (1.4 deg) and its margin in coarse voxels. */
constexpr int kFreeSpaceBandwidth = 128;
constexpr double kFreeSpaceMargin = 1.0;
/** The indexes and pass-1 occupancy keep one point per cube of radius / this. */
constexpr double kIndexThinning = 8.0;
/** Bandwidth of the magnitude shells (5.6 deg cells; the polish refines) and the
 *  peaks they add: on the bunny views the truth lay within the first ten. */
constexpr int kMagnitudeBandwidth = 32;
constexpr int kMagnitudeCandidates = 10;

/** The target's spectra, grids, indexes and free space, relative to its projection
 *  center. */
struct TargetModel {
  StageSettings settings; ///< what it was prepared with
  SphericalSpectrum spherical;
  SphericalSupport spherical_support; ///< for the normalized refinement
  double spherical_norm = 0.0;
  SphericalSpectrum orientation;  ///< surface-orientation histogram (may be empty)
  SpatialSpectrum coarse, fine;   ///< occupancy: padded whole target; inner region
  SpatialSpectrumF coarse_single; ///< coarse rounded to float: pass 1's correlations
  double coarse_energy = 0.0, fine_energy = 0.0; ///< spectrumEnergy of coarse and fine
  PointIndex index;                              ///< target points, for verifyPose
  PointIndex reach_index; ///< at kReachVoxels (sensor-centered only)
  double thickness = 0.0; ///< SurfacePatches::thickness of the target
  FreeSpace free_space; ///< what the target's sensor saw through (sensor-centered only)
  Eigen::Matrix3Xd samples; ///< for the reverse free-space test (sensor-centered only)
  Eigen::VectorXd sample_weights;
  MagnitudeShells magnitude; ///< of the coarse occupancy (magnitudeShells)
  double preparation_ms = 0.0;
};

/** Whether a model prepared with \a prepared serves \a wanted: the same grids,
 *  bandwidths, passes, fusion levels, normalized refinement, orientation candidates
 *  and mode (the thread count, the search's other settings and the limits aside). */
bool sameModel(const StageSettings& prepared, const StageSettings& wanted);

/** The model of a target whose \a points are relative to its projection center;
 *  the same for any thread count. */
std::shared_ptr<const TargetModel> prepareTarget(const Eigen::Matrix3Xd& points,
                                                 const StageSettings& settings,
                                                 const ChannelValues& channels);

/** One sample per cube of \a radius (voxelCentroids); every k-th beyond 16,384. */
Eigen::Matrix3Xd verificationSamples(const Eigen::Matrix3Xd& points, double radius);

} // namespace pcl::phaser::detail
