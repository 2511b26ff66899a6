/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: a cloud's spherical and occupancy spectra as the stages make
// them.
#include "channels/cloud_signals.h"
#include "pipeline/stage_settings.h"
#include "spatial/spatial_correlation.h"
#include "spatial/spatial_single.h"
#include "sphere/spherical_harmonics.h"

#include <pcl_phaser/core/result.h>

namespace pcl::phaser::detail {

/** The fused spherical spectrum (bandwidth, fusion_levels of \a settings; with
 *  \a support if given) of the \a which cloud on \a num_threads threads; its sampling
 *  and transform times into \a times.
 *  \throws InvalidArgument when the cloud carries no spherical signal */
SphericalSpectrum sphericalSpectrum(const Eigen::Matrix3Xd& points,
                                    const ChannelValues& channels,
                                    const StageSettings& settings, int num_threads,
                                    const char* which, StageTimes& times,
                                    SphericalSupport* support = nullptr);
/** Binary occupancy spectrum of \a points on \a grid. */
SpatialSpectrum occupancySpectrum(const SpatialGrid& grid,
                                  const Eigen::Matrix3Xd& points, int num_threads);
/** occupancySpectrum in single precision (pass 1's correlations). */
SpatialSpectrumF occupancySpectrumSingle(const SpatialGrid& grid,
                                         const Eigen::Matrix3Xd& points,
                                         int num_threads);

} // namespace pcl::phaser::detail
