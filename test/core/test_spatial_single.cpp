/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Pass 1's single-precision correlation against the double one: the split FFT on odd
 * and even dims (odd ny * nz makes the float x slabs cycle through four alignments),
 * independent of the thread count, and the whitened correlation's peak.
 */
#include "spatial/spatial_single.h"
#include "spatial_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace pcl::phaser;
using pcl::phaser::test::randomVolume;
using namespace pcl::phaser::detail;
using pcl::phaser::test::sceneBox;

namespace {

SpatialVolumeF rounded(const SpatialVolume& v)
{
  SpatialVolumeF f;
  f.grid = v.grid;
  f.values.assign(v.values.begin(), v.values.end());
  return f;
}

} // namespace

TEST(SpatialSingle, FftMatchesDoubleAndThreadsDoNotMatter)
{
  for (const Eigen::Vector3i& dims :
       {Eigen::Vector3i(5, 7, 9), Eigen::Vector3i(9, 3, 5), Eigen::Vector3i(8, 6, 12),
        Eigen::Vector3i(5, 32, 6)}) {
    const SpatialVolume v = randomVolume(dims, 7);
    const SpatialSpectrum D = computeSpectrum(v, 1);
    const SpatialSpectrumF F1 = computeSpectrum(rounded(v), 1);
    ASSERT_EQ(F1.coefficients.size(), D.coefficients.size());
    double worst = 0.0, largest = 0.0;
    for (std::size_t i = 0; i < D.coefficients.size(); ++i) {
      const std::complex<double> f(F1.coefficients[i]);
      worst = std::max(worst, std::abs(f - D.coefficients[i]));
      largest = std::max(largest, std::abs(D.coefficients[i]));
    }
    EXPECT_LT(worst, 1e-5 * largest) << dims.transpose();
    // Correlating with a unit impulse gives the volume back (the c2r undoes the r2c).
    SpatialVolume delta = randomVolume(dims, 8);
    std::fill(delta.values.begin(), delta.values.end(), 0.0);
    delta.values[0] = 1.0;
    const SpatialVolumeF c1 =
        correlateSpectraWhitened(F1, computeSpectrum(rounded(delta), 1), 0.0, 1);
    double back = 0.0;
    for (std::size_t i = 0; i < v.values.size(); ++i)
      back = std::max(back, std::abs(c1.values[i] - v.values[i]));
    EXPECT_LT(back, 1e-5) << dims.transpose();
    for (int threads : {2, 3}) {
      const SpatialSpectrumF Ft = computeSpectrum(rounded(v), threads);
      ASSERT_EQ(0, std::memcmp(Ft.coefficients.data(), F1.coefficients.data(),
                               F1.coefficients.size() * sizeof(std::complex<float>)));
      const SpatialVolumeF ct = correlateSpectraWhitened(
          Ft, computeSpectrum(rounded(delta), threads), 0.0, threads);
      ASSERT_EQ(0, std::memcmp(ct.values.data(), c1.values.data(),
                               c1.values.size() * sizeof(float)));
    }
  }
}

TEST(SpatialSingle, WhitenedPeakMatchesDouble)
{
  // A 40 x 30 x 8 m scene and the same moved by a non-integer shift, on a 128 grid:
  // the single-precision pass finds the voxel of the double one and a shift within
  // 0.01 voxel of it.
  const Eigen::Matrix3Xd source = sceneBox(6000, 3);
  const Eigen::Vector3d shift(2.37, -1.61, 0.43);
  const Eigen::Matrix3Xd target = source.colwise() + shift;
  SpatialGridParameters parameters;
  parameters.grid_size = 128;
  const SpatialGrid grid = makeSpatialGrid(target, parameters);
  SpatialVoxelParameters voxel;
  voxel.saturation = 0.05;
  const SpatialVolume vt = voxelize(grid, target, voxel);
  const SpatialVolumeF vt_single = voxelizeSingle(grid, target, voxel);
  double worst = 0.0;
  for (std::size_t i = 0; i < vt.values.size(); ++i)
    worst = std::max(worst, std::abs(vt_single.values[i] - vt.values[i]));
  EXPECT_LT(worst, 1e-6);
  const SpatialSpectrum T = computeSpectrum(vt);
  const SpatialCorrelationResult d = findSpatialPeak(
      correlateSpectraWhitened(T, computeSpectrum(voxelize(grid, source, voxel)), 0.5));
  const SpatialCorrelationResult f = findSpatialPeak(correlateSpectraWhitened(
      singlePrecision(T), computeSpectrum(voxelizeSingle(grid, source, voxel)), 0.5));
  EXPECT_EQ(f.index, d.index);
  EXPECT_LT(((f.shift - d.shift) / grid.voxel_size).cwiseAbs().maxCoeff(), 0.01);
  EXPECT_NEAR(f.peak_value, d.peak_value, 1e-4 * d.peak_value);
  EXPECT_LT(((f.shift - shift) / grid.voxel_size).cwiseAbs().maxCoeff(), 0.15);
  const std::vector<SpatialCorrelationResult> peaks = findDistinctSpatialPeaks(
      correlateSpectraWhitened(singlePrecision(T),
                               computeSpectrum(voxelizeSingle(grid, source, voxel)),
                               0.5),
      3, 3);
  ASSERT_FALSE(peaks.empty());
  EXPECT_EQ(peaks[0].index, f.index);
}
