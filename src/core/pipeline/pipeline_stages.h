/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: the steps the passes share (pipeline_stages.cpp).
#include "pipeline/stage_state.h"

namespace pcl::phaser::detail {

/** The fused spherical spectrum (with \a support if given) of the \a which cloud.
 *  \throws InvalidArgument when the cloud carries no spherical signal */
SphericalSpectrum sphericalSpectrum(const Eigen::Matrix3Xd& points,
                                    const ChannelValues& channels,
                                    const PhaserParameters& params, const char* which,
                                    StageTimes& times,
                                    SphericalSupport* support = nullptr);
/** Binary occupancy spectrum of \a points on \a grid. */
SpatialSpectrum occupancySpectrum(const SpatialGrid& grid,
                                  const Eigen::Matrix3Xd& points, int num_threads);

/** Verification of (R, t) on \a threads threads, both ways (reverse: sensor origins).
 */
Verification verifyBothWays(const SourceContext& source, const Eigen::Matrix3d& R,
                            const Eigen::Vector3d& t, StageTimes& times, int threads);
/** Translation of \a points onto \a target at the whitened correlation's sub-voxel
 *  peak, no longer than \a max_shift; with \a volume the plain correlation kept and
 *  the sidelobe score computed. */
SpatialCorrelationResult
correlateTranslation(const SpatialSpectrum& target, const Eigen::Matrix3Xd& points,
                     double whitening, int num_threads, StageTimes& times,
                     SpatialVolume* volume = nullptr, double* source_energy = nullptr,
                     double max_shift = std::numeric_limits<double>::infinity());
/** The longest pass-1 shift: the region's radius and a coarse voxel (the sensor sits
 *  at the centered origin), else unbounded. */
double maxShift(const SourceContext& source);
/** \a pose refined on the verification samples (refinePoseWithin: within the
 *  hypothesis separation and two coarse voxels), kept when it ranks higher. */
Pose refineOnSamples(const SourceContext& source, const Pose& pose, StageTimes& times,
                     int num_threads, bool all_samples = false);
/** Later passes from \a pose's viewpoint, kept while they verify better (\a passes). */
Pose reprojectionPasses(const SourceContext& source, Pose pose, int& passes,
                        StageTimes& times);
/** The final rotation refinement (not when \a decided) and shift (kept when they verify
 *  better) and the local refinement; scores, translation covariance and rotation
 *  samples into \a result. */
Pose refineFinalPose(const SourceContext& source, Pose pose, bool decided,
                     PhaserResult& result);

} // namespace pcl::phaser::detail
