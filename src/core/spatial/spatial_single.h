/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Pass 1's coarse translation correlations in single precision (libfftw3f): half the
 * memory traffic of every step and a faster FFT. The same algorithms as the double
 * functions of spatial_correlation.h (shared templates); the fine grid, the final
 * correlation and the covariance stay in double.
 */
#pragma once

#include "spatial/spatial_correlation.h"

#include <complex>
#include <vector>

namespace pcl::phaser::detail {

using SpatialRealArrayF = std::vector<float, SpatialAllocator<float>>;
using SpatialComplexArrayF =
    std::vector<std::complex<float>, SpatialAllocator<std::complex<float>>>;

/** \brief SpatialVolume in single precision. */
struct SpatialVolumeF {
  SpatialGrid grid;
  SpatialRealArrayF values; ///< grid.size() values in flatIndex order
};

/** \brief SpatialSpectrum in single precision (the same r2c layout). */
struct SpatialSpectrumF {
  SpatialGrid grid;
  SpatialComplexArrayF coefficients;

  int halfZ() const { return grid.dims.z() / 2 + 1; }
};

/** \brief \a spectrum rounded to single precision (a target's, once per target). */
SpatialSpectrumF singlePrecision(const SpatialSpectrum& spectrum);

/** \brief voxelize into single precision: the same weights, summed in float. */
SpatialVolumeF voxelizeSingle(const SpatialGrid& grid, const Eigen::Matrix3Xd& points,
                              const SpatialVoxelParameters& parameters = {});

/** \brief computeSpectrum in single precision. */
SpatialSpectrumF computeSpectrum(const SpatialVolumeF& volume, int num_threads = 1);

/** \brief correlateSpectraWhitened in single precision. */
SpatialVolumeF correlateSpectraWhitened(const SpatialSpectrumF& target,
                                        SpatialSpectrumF&& source, double exponent,
                                        int num_threads = 1);

/** \brief findSpatialPeak of a single-precision volume, without the score. */
SpatialCorrelationResult
findSpatialPeak(const SpatialVolumeF& correlation,
                SpatialPeakRefinement refinement = SpatialPeakRefinement::kGaussian,
                int num_threads = 1);

/** \brief findDistinctSpatialPeaks of a single-precision volume. */
std::vector<SpatialCorrelationResult> findDistinctSpatialPeaks(
    const SpatialVolumeF& correlation, int count, int separation,
    SpatialPeakRefinement refinement = SpatialPeakRefinement::kGaussian);

} // namespace pcl::phaser::detail
