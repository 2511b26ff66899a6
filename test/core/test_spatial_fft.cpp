/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The split 3-D FFT of the translation stage against a direct DFT, on odd and even
 * dims (odd ny * nz makes the x slabs alternate between two memory alignments; ny *
 * (nz/2+1) a multiple of 64 gathers the rows along x into a compact buffer), and its
 * independence of the thread count.
 */
#include "spatial/spatial_correlation.h"
#include "spatial_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstring>
#include <limits>
#include <random>

using namespace pcl::phaser;
using pcl::phaser::test::randomVolume;

namespace {

/** The half-spectrum entry (kx, ky, kz) by the definition: sum f e^{-2 pi i k.x/n}. */
std::complex<double> directDft(const SpatialVolume& v, int kx, int ky, int kz)
{
  const Eigen::Vector3i& n = v.grid.dims;
  std::complex<double> sum = 0.0;
  for (int x = 0; x < n.x(); ++x)
    for (int y = 0; y < n.y(); ++y)
      for (int z = 0; z < n.z(); ++z) {
        const double phase =
            -2.0 * M_PI *
            (static_cast<double>(kx) * x / n.x() + static_cast<double>(ky) * y / n.y() +
             static_cast<double>(kz) * z / n.z());
        sum += v.values[v.grid.flatIndex(x, y, z)] * std::polar(1.0, phase);
      }
  return sum;
}

/** Largest difference between computeSpectrum(v) (two threads) and the direct DFT. */
double worstDftError(const SpatialVolume& v)
{
  const Eigen::Vector3i& dims = v.grid.dims;
  const SpatialSpectrum S = computeSpectrum(v, 2);
  const int hz = S.halfZ();
  if (S.coefficients.size() != static_cast<std::size_t>(dims.x()) * dims.y() * hz)
    return std::numeric_limits<double>::infinity();
  double worst = 0.0;
  for (int kx = 0; kx < dims.x(); ++kx)
    for (int ky = 0; ky < dims.y(); ++ky)
      for (int kz = 0; kz < hz; ++kz) {
        const std::complex<double> got =
            S.coefficients[(static_cast<std::size_t>(kx) * dims.y() + ky) * hz + kz];
        worst = std::max(worst, std::abs(got - directDft(v, kx, ky, kz)));
      }
  return worst;
}

} // namespace

TEST(SpatialFft, MatchesTheDirectDftOnOddAndEvenDims)
{
  for (const Eigen::Vector3i& dims :
       {Eigen::Vector3i(5, 7, 9), Eigen::Vector3i(6, 5, 8), Eigen::Vector3i(4, 6, 10),
        Eigen::Vector3i(3, 16, 6)})
    EXPECT_LT(worstDftError(randomVolume(dims, 3)), 1e-9) << dims.transpose();
}

TEST(SpatialFft, InverseUndoesForwardAndThreadsDoNotMatter)
{
  // Correlating with a unit impulse at the origin gives the volume back, so the c2r
  // undoes the r2c: C(lag) = sum_x f(x + lag) d(x) = f(lag).
  for (const Eigen::Vector3i& dims :
       {Eigen::Vector3i(9, 7, 5), Eigen::Vector3i(8, 6, 12),
        Eigen::Vector3i(5, 32, 6)}) {
    const SpatialVolume f = randomVolume(dims, 5);
    SpatialVolume delta = randomVolume(dims, 6);
    std::fill(delta.values.begin(), delta.values.end(), 0.0);
    delta.values[0] = 1.0;
    const SpatialSpectrum F1 = computeSpectrum(f, 1);
    const SpatialVolume c1 = correlateSpectra(F1, computeSpectrum(delta, 1), 1);
    double worst = 0.0;
    for (std::size_t i = 0; i < f.values.size(); ++i)
      worst = std::max(worst, std::abs(c1.values[i] - f.values[i]));
    EXPECT_LT(worst, 1e-12) << dims.transpose();
    for (int threads : {2, 3, 8}) {
      const SpatialSpectrum Ft = computeSpectrum(f, threads);
      ASSERT_EQ(0, std::memcmp(Ft.coefficients.data(), F1.coefficients.data(),
                               F1.coefficients.size() * sizeof(std::complex<double>)));
      const SpatialVolume ct =
          correlateSpectra(Ft, computeSpectrum(delta, threads), threads);
      ASSERT_EQ(0, std::memcmp(ct.values.data(), c1.values.data(),
                               c1.values.size() * sizeof(double)));
    }
  }
}

TEST(SpatialFft, EmptySlabsTransformLikeTheRest)
{
  // A source's occupancy leaves the padding empty: the zero x slabs are skipped (their
  // 2-D transforms are zero), which must give the DFT still, on either slab alignment.
  for (const Eigen::Vector3i& dims :
       {Eigen::Vector3i(7, 5, 9), Eigen::Vector3i(8, 6, 8)}) {
    SpatialVolume v = randomVolume(dims, 11);
    for (int x : {0, 1, 4, dims.x() - 1})
      for (int y = 0; y < dims.y(); ++y)
        for (int z = 0; z < dims.z(); ++z)
          v.values[v.grid.flatIndex(x, y, z)] = 0.0;
    EXPECT_LT(worstDftError(v), 1e-9) << dims.transpose();
  }
}
