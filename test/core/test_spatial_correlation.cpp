/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Translation stage: r2c spectra, correlation, sub-voxel
 * peak (reference-implementation-notes.md section 4 and the bugs listed there).
 */
#include "spatial/spatial_correlation.h"
#include "spatial/spatial_grid_support.h"
#include "spatial_test_support.h"
#include "support/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <thread>

using namespace pcl::phaser;
using namespace pcl::phaser::test;

namespace {

/** Signed integer frequency (kx, ky, kz) of stored coefficient \a flat: kx in
 *  (-nx/2, nx/2], ky likewise, kz in [0, nz/2]. */
Eigen::Vector3i frequencyIndex(const SpatialSpectrum& s, std::size_t flat)
{
  const std::size_t hz = static_cast<std::size_t>(s.halfZ());
  const std::size_t ny = static_cast<std::size_t>(s.grid.dims.y());
  const Eigen::Vector3i k(static_cast<int>(flat / (ny * hz)),
                          static_cast<int>((flat / hz) % ny),
                          static_cast<int>(flat % hz));
  return {detail::wrapLag(k.x(), s.grid.dims.x()),
          detail::wrapLag(k.y(), s.grid.dims.y()), k.z()};
}

/** Shift found when the target is the source moved by \a shift. */
SpatialCorrelationResult recoverShift(const Eigen::Matrix3Xd& source,
                                      const Eigen::Vector3d& shift, int grid_size,
                                      SpatialPeakRefinement refinement,
                                      SpatialGrid* grid_out = nullptr)
{
  const Eigen::Matrix3Xd target = source.colwise() + shift;
  SpatialGridParameters params;
  params.grid_size = grid_size;
  const SpatialGrid grid = makeSpatialGrid(target, params);
  if (grid_out)
    *grid_out = grid;
  const SpatialSpectrum t = computeSpectrum(voxelize(grid, target));
  const SpatialSpectrum s = computeSpectrum(voxelize(grid, source));
  return correlateSpatial(t, s, refinement);
}

} // namespace

// ---------------------------------------------------------------------------------------
TEST(SpatialSpectrum, LayoutAndFrequencies)
{
  // A single complex exponential's real part puts N/2 at +k and its conjugate at -k.
  SpatialVolume v = zeroVolume(Eigen::Vector3i(8, 6, 10), 0.5);
  const Eigen::Vector3i k(-3, 2, 4);
  for (std::size_t i = 0; i < v.values.size(); ++i) {
    const Eigen::Vector3i x = v.grid.voxelIndex(i);
    double phase = 0.0;
    for (int a = 0; a < 3; ++a)
      phase += 2.0 * M_PI * k[a] * x[a] / v.grid.dims[a];
    v.values[i] = std::cos(phase) + 0.25;
  }
  const SpatialSpectrum s = computeSpectrum(v);
  ASSERT_EQ(s.coefficients.size(), 8u * 6u * 6u);
  EXPECT_EQ(s.halfZ(), 6);
  const double n = static_cast<double>(v.grid.size());
  EXPECT_NEAR(s.coefficients[0].real(), 0.25 * n, 1e-9); // DC = sum of values
  for (std::size_t i = 0; i < s.coefficients.size(); ++i) {
    const Eigen::Vector3i f = frequencyIndex(s, i);
    const double expected = (f == k || f == -k) ? 0.5 * n : (i == 0 ? 0.25 * n : 0.0);
    EXPECT_NEAR(std::abs(s.coefficients[i]), expected, 1e-9) << f.transpose();
  }
  // kz >= 0, so k itself is stored: kx = -3 in row 8 - 3 = 5, ky = 2, kz = 4.
  const std::size_t flat = (static_cast<std::size_t>(5) * 6 + 2) * 6 + 4;
  EXPECT_EQ(frequencyIndex(s, flat), k);
  EXPECT_NEAR(std::abs(s.coefficients[flat]), 0.5 * n, 1e-9);
  EXPECT_EQ(s.multiplicity(flat), 2);
  EXPECT_EQ(s.multiplicity(5), 1); // kz = nz / 2
  EXPECT_EQ(s.multiplicity(6), 1); // kz = 0 of the next row
  EXPECT_THROW(computeSpectrum(SpatialVolume{v.grid, SpatialRealArray(7)}),
               InvalidArgument);
}

// ---------------------------------------------------------------------------------------
TEST(SpatialCorrelation, DeltaShiftsInEveryOctantWrapAround)
{
  const Eigen::Vector3i dims(16, 12, 10);
  const Eigen::Vector3i p(5, 7, 3);
  for (int sx : {-1, 1})
    for (int sy : {-1, 1})
      for (int sz : {-1, 1})
        for (const Eigen::Vector3i& m :
             {Eigen::Vector3i(3, 2, 1), Eigen::Vector3i(7, 5, 4)}) {
          const Eigen::Vector3i t(sx * m.x(), sy * m.y(), sz * m.z());
          SpatialVolume f = zeroVolume(dims), g = zeroVolume(dims);
          Eigen::Vector3i q;
          for (int a = 0; a < 3; ++a)
            q[a] = ((p[a] + t[a]) % dims[a] + dims[a]) % dims[a];
          f.values[f.grid.flatIndex(q.x(), q.y(), q.z())] = 1.0; // target = source + t
          g.values[g.grid.flatIndex(p.x(), p.y(), p.z())] = 1.0;
          const SpatialCorrelationResult r = correlateSpatial(
              computeSpectrum(f), computeSpectrum(g), SpatialPeakRefinement::kGaussian);
          for (int a = 0; a < 3; ++a)
            EXPECT_EQ(r.index[a], (t[a] + dims[a]) % dims[a]) << t.transpose();
          EXPECT_TRUE(r.lag.isApprox(t.cast<double>(), 1e-12)) << t.transpose();
          EXPECT_TRUE(r.shift.isApprox(0.5 * t.cast<double>(), 1e-12)); // index * voxel
          EXPECT_NEAR(r.peak_value, 1.0, 1e-12);
          EXPECT_GT(r.score, 1e6);
        }
}

TEST(SpatialCorrelation, DifferentOriginsEnterTheShift)
{
  // Source voxelized on a grid moved by whole voxels: the correlation volume's origin
  // (target origin - source origin) carries that offset into the metric shift.
  const Eigen::Matrix3Xd source = sceneBox(3000, 5);
  const Eigen::Vector3d shift(2.2, -1.1, 0.3);
  const Eigen::Matrix3Xd target = source.colwise() + shift;
  SpatialGridParameters params;
  params.grid_size = 64;
  const SpatialGrid tg = makeSpatialGrid(target, params);
  SpatialGrid sg = tg;
  sg.origin -= Eigen::Vector3d(3.0, -2.0, 1.0) * tg.voxel_size;
  const SpatialCorrelationResult r = correlateSpatial(
      computeSpectrum(voxelize(tg, target)), computeSpectrum(voxelize(sg, source)));
  EXPECT_LT((r.shift - shift).cwiseAbs().maxCoeff(), 0.15 * tg.voxel_size);
}

TEST(SpatialCorrelation, RandomCloudSubVoxelAccuracy)
{
  // 4000 points in 40 x 30 x 8 m, non-integer shifts in all directions. Observed worst
  // axis error over these shifts, in voxels, at grid_size 64 (64x50x15, 1.29 m voxels)
  // and 128 (128x100x30, 0.63 m): no refinement 0.50 / 0.50, parabolic 0.10 / 0.10,
  // Gaussian 0.095 / 0.055. Tolerance 0.15 voxel.
  const Eigen::Matrix3Xd source = sceneBox(4000, 6);
  const std::vector<Eigen::Vector3d> shifts = {
      {2.37, -1.61, 0.43},  {-3.52, 2.18, -0.77}, {0.66, 0.31, -1.24},
      {-1.05, -2.94, 0.19}, {5.8, 4.4, 1.6},      {-7.3, -0.5, -0.6}};
  const SpatialPeakRefinement methods[] = {SpatialPeakRefinement::kNone,
                                           SpatialPeakRefinement::kParabolic,
                                           SpatialPeakRefinement::kGaussian};
  for (int grid_size : {64, 128}) {
    double worst[3] = {0, 0, 0};
    for (const Eigen::Vector3d& shift : shifts) {
      for (int m = 0; m < 3; ++m) {
        SpatialGrid grid;
        const SpatialCorrelationResult r =
            recoverShift(source, shift, grid_size, methods[m], &grid);
        const double error =
            ((r.shift - shift) / grid.voxel_size).cwiseAbs().maxCoeff();
        worst[m] = std::max(worst[m], error);
        // One grid for both clouds: the lag-0 shift is 0, so shift = lag * voxel.
        EXPECT_TRUE(r.shift.isApprox(r.lag * grid.voxel_size, 1e-12));
      }
    }
    EXPECT_LT(worst[0], 0.55) << grid_size;
    EXPECT_LT(worst[1], 0.15) << grid_size;
    EXPECT_LT(worst[2], 0.15) << grid_size;
    EXPECT_LT(worst[2], worst[0] / 3.0) << grid_size;
  }
}

TEST(SpatialCorrelation, SwappingSourceAndTargetNegatesTheShift)
{
  const Eigen::Matrix3Xd source = sceneBox(4000, 7);
  const Eigen::Matrix3Xd target = source.colwise() + Eigen::Vector3d(-2.71, 1.93, 0.58);
  SpatialGridParameters params;
  params.grid_size = 64;
  const SpatialGrid grid = makeSpatialGrid(target, params);
  const SpatialSpectrum t = computeSpectrum(voxelize(grid, target));
  const SpatialSpectrum s = computeSpectrum(voxelize(grid, source));
  for (auto method :
       {SpatialPeakRefinement::kParabolic, SpatialPeakRefinement::kGaussian}) {
    const SpatialCorrelationResult ab = correlateSpatial(t, s, method);
    const SpatialCorrelationResult ba = correlateSpatial(s, t, method);
    EXPECT_LT((ab.shift + ba.shift).norm(), 1e-9);
    EXPECT_NEAR(ab.peak_value, ba.peak_value, 1e-9 * ab.peak_value);
  }
}

TEST(SpatialCorrelation, ReVoxelisingTheMovedSourceRemovesTheInterpolationBias)
{
  // The per-axis interpolators are unbiased at zero offset, so moving the source by the
  // estimate and correlating again leaves a much smaller residual (2 rounds: ~0.002
  // voxel).
  const Eigen::Matrix3Xd source = sceneBox(4000, 8);
  const Eigen::Vector3d shift(3.14, -2.27, 0.61);
  const Eigen::Matrix3Xd target = source.colwise() + shift;
  SpatialGridParameters params;
  params.grid_size = 64;
  const SpatialGrid grid = makeSpatialGrid(target, params);
  const SpatialSpectrum t = computeSpectrum(voxelize(grid, target));
  Eigen::Vector3d estimate = Eigen::Vector3d::Zero();
  double first_error = 0.0;
  for (int round = 0; round < 3; ++round) {
    const Eigen::Matrix3Xd moved = source.colwise() + estimate;
    estimate += correlateSpatial(t, computeSpectrum(voxelize(grid, moved))).shift;
    if (round == 0)
      first_error = (estimate - shift).cwiseAbs().maxCoeff() / grid.voxel_size;
  }
  const double final_error = (estimate - shift).cwiseAbs().maxCoeff() / grid.voxel_size;
  EXPECT_LT(final_error, 0.02);
  EXPECT_LT(final_error, 0.5 * first_error);
}

TEST(SpatialCorrelation, SourcePointsOutsideTheTargetGridAreIgnored)
{
  // Extra source points far outside the target's grid (in every direction, including
  // negative indices) must not change the voxelized source at all.
  const Eigen::Matrix3Xd source = sceneBox(3000, 9);
  const Eigen::Vector3d shift(1.7, 0.9, -0.4);
  const Eigen::Matrix3Xd target = source.colwise() + shift;
  SpatialGridParameters params;
  params.grid_size = 64;
  const SpatialGrid grid = makeSpatialGrid(target, params);
  Eigen::Matrix3Xd extra = randomBox(3000, Eigen::Vector3d(200.0, 200.0, 50.0), 10);
  Eigen::Index kept = 0;
  for (Eigen::Index i = 0; i < extra.cols(); ++i) {
    const Eigen::Array3d u = (extra.col(i) - grid.origin).array() / grid.voxel_size;
    if ((u < -1.0).any() || (u > grid.dims.cast<double>().array() + 1.0).any())
      extra.col(kept++) = extra.col(i);
  }
  ASSERT_GT(kept, 2000);
  Eigen::Matrix3Xd with_extra(3, source.cols() + kept);
  with_extra << source, extra.leftCols(kept);
  const SpatialVolume a = voxelize(grid, source), b = voxelize(grid, with_extra);
  EXPECT_TRUE(bitIdentical(a.values, b.values));
  const SpatialCorrelationResult r =
      correlateSpatial(computeSpectrum(voxelize(grid, target)), computeSpectrum(b));
  EXPECT_LT((r.shift - shift).cwiseAbs().maxCoeff(), 0.15 * grid.voxel_size);
}

TEST(SpatialCorrelation, ScoreSeparatesMatchFromUnrelatedClouds)
{
  const Eigen::Matrix3Xd source = sceneBox(4000, 11);
  const Eigen::Matrix3Xd target = source.colwise() + Eigen::Vector3d(1.2, 2.3, 0.1);
  const Eigen::Matrix3Xd unrelated = sceneBox(4000, 12);
  SpatialGridParameters params;
  params.grid_size = 64;
  const SpatialGrid grid = makeSpatialGrid(target, params);
  const SpatialSpectrum t = computeSpectrum(voxelize(grid, target));
  const double match =
      correlateSpatial(t, computeSpectrum(voxelize(grid, source))).score;
  const double noise =
      correlateSpatial(t, computeSpectrum(voxelize(grid, unrelated))).score;
  EXPECT_GT(match, 2.0 * noise);
  EXPECT_GT(noise, 0.0);
}

TEST(SpatialCorrelation, EmptyInputGivesZeroGridAndZeroScore)
{
  const Eigen::Matrix3Xd target = sceneBox(1000, 13);
  SpatialGridParameters params;
  params.grid_size = 32;
  const SpatialGrid grid = makeSpatialGrid(target, params);
  const SpatialVolume empty = voxelize(grid, Eigen::Matrix3Xd(3, 0));
  for (double x : empty.values)
    ASSERT_EQ(x, 0.0);
  const SpatialCorrelationResult r =
      correlateSpatial(computeSpectrum(voxelize(grid, target)), computeSpectrum(empty));
  EXPECT_EQ(r.peak_value, 0.0);
  EXPECT_EQ(r.score, 0.0);
  EXPECT_EQ(r.index, Eigen::Vector3i::Zero());
  EXPECT_EQ(r.shift, Eigen::Vector3d::Zero());
}

TEST(SpatialCorrelation, BadArgumentsThrow)
{
  const SpatialSpectrum a = computeSpectrum(zeroVolume(Eigen::Vector3i(8, 8, 8)));
  const SpatialSpectrum b = computeSpectrum(zeroVolume(Eigen::Vector3i(8, 8, 10)));
  const SpatialSpectrum c = computeSpectrum(zeroVolume(Eigen::Vector3i(8, 8, 8), 0.7));
  EXPECT_THROW(correlateSpectra(a, b), InvalidArgument);
  EXPECT_THROW(correlateSpectra(a, c), InvalidArgument);
  EXPECT_THROW(correlateSpectra(a, a, -1), InvalidArgument);
  SpatialSpectrum truncated = a;
  truncated.coefficients.pop_back();
  EXPECT_THROW(correlateSpectra(a, truncated), InvalidArgument);
  SpatialVolume wrong = zeroVolume(Eigen::Vector3i(8, 8, 8));
  wrong.values.pop_back();
  EXPECT_THROW(findSpatialPeak(wrong), InvalidArgument);
  EXPECT_THROW(findSpatialPeak(zeroVolume(Eigen::Vector3i(8, 8, 8)),
                               SpatialPeakRefinement::kNone, -2),
               InvalidArgument);
}

TEST(SpatialCorrelation, WhitenedProductIsTheCrossPowerOverItsRootMagnitude)
{
  // The default whitening (exponent 1/2) against its definition, on random spectra with
  // zero bins (there the product is 0, not NaN): correlating F conj(G) / |F
  // conj(G)|^(1/2) plainly with an all-ones spectrum gives the same volume.
  const Eigen::Vector3i dims(6, 5, 8);
  std::mt19937 rng(21);
  std::normal_distribution<double> n;
  SpatialSpectrum F = computeSpectrum(zeroVolume(dims));
  SpatialSpectrum G = F, expected = F, ones = F;
  for (std::size_t i = 0; i < F.coefficients.size(); ++i) {
    F.coefficients[i] = {n(rng), n(rng)};
    G.coefficients[i] = i % 7 == 3 ? 0.0 : std::complex<double>(n(rng), n(rng));
    const std::complex<double> c = F.coefficients[i] * std::conj(G.coefficients[i]);
    expected.coefficients[i] = std::abs(c) > 0.0 ? c / std::sqrt(std::abs(c)) : 0.0;
    ones.coefficients[i] = 1.0;
  }
  const SpatialVolume want = correlateSpectra(expected, ones, 1);
  for (int threads : {1, 3}) {
    const SpatialVolume got =
        correlateSpectraWhitened(F, SpatialSpectrum(G), 0.5, threads);
    ASSERT_EQ(got.values.size(), want.values.size());
    double worst = 0.0, largest = 0.0;
    for (std::size_t i = 0; i < want.values.size(); ++i) {
      ASSERT_TRUE(std::isfinite(got.values[i]));
      worst = std::max(worst, std::abs(got.values[i] - want.values[i]));
      largest = std::max(largest, std::abs(want.values[i]));
    }
    EXPECT_LT(worst, 1e-12 * largest) << threads << " threads";
  }
}

TEST(SpatialCorrelation, ConcurrentCorrelationsMatchSerialOnes)
{
  // Two threads execute the cached plans at once (new-array interface), with different
  // grid sizes so one of them may be planning while the other executes.
  const Eigen::Matrix3Xd source = sceneBox(3000, 14);
  const Eigen::Vector3d shift(-1.9, 2.6, 0.35);
  const auto run = [&](int grid_size) {
    return recoverShift(source, shift, grid_size, SpatialPeakRefinement::kGaussian);
  };
  SpatialCorrelationResult concurrent[2];
  std::thread first([&] { concurrent[0] = run(48); });
  std::thread second([&] { concurrent[1] = run(40); });
  first.join();
  second.join();
  const SpatialCorrelationResult serial[2] = {run(48), run(40)};
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(concurrent[i].shift, serial[i].shift);
    EXPECT_EQ(concurrent[i].score, serial[i].score);
  }
}

// Four bumps on a 16^3 volume: A (height 3), B (2.5, two voxels from A), C (2), D (1).
// The distinct peaks are taken highest first, skipping those within the separation of
// one taken; each is refined on its own bump.
TEST(SpatialCorrelation, DistinctPeaksHighestFirstAndApart)
{
  SpatialVolume v;
  v.grid.dims = Eigen::Vector3i(16, 16, 16);
  v.grid.voxel_size = 1.0;
  v.values.assign(v.grid.size(), 0.0);
  const std::vector<std::pair<Eigen::Vector3i, double>> bumps = {
      {{4, 4, 4}, 3.0}, {{6, 4, 4}, 2.5}, {{12, 10, 3}, 2.0}, {{2, 13, 9}, 1.0}};
  for (int x = 0; x < 16; ++x)
    for (int y = 0; y < 16; ++y)
      for (int z = 0; z < 16; ++z)
        for (const auto& [c, h] : bumps) {
          const double d2 = (Eigen::Vector3i(x, y, z) - c).squaredNorm();
          v.values[v.grid.flatIndex(x, y, z)] += h * std::exp(-d2 / (2 * 0.5 * 0.5));
        }
  auto lags = [](const std::vector<SpatialCorrelationResult>& peaks) {
    std::vector<Eigen::Vector3i> out;
    for (const SpatialCorrelationResult& p : peaks) {
      EXPECT_LT((p.lag - p.lag.array().round().matrix()).norm(), 0.25); // sub-voxel
      out.push_back(p.index);
    }
    return out;
  };
  const std::vector<Eigen::Vector3i> apart = lags(findDistinctSpatialPeaks(v, 3, 3));
  ASSERT_EQ(apart.size(), 3u);
  EXPECT_EQ(apart[0], bumps[0].first);
  EXPECT_EQ(apart[1], bumps[2].first); // B is within 3 voxels of A
  EXPECT_EQ(apart[2], bumps[3].first);
  const std::vector<Eigen::Vector3i> close = lags(findDistinctSpatialPeaks(v, 3, 1));
  ASSERT_EQ(close.size(), 3u);
  EXPECT_EQ(close[1], bumps[1].first);
  EXPECT_EQ(close[2], bumps[2].first);
  EXPECT_EQ(findDistinctSpatialPeaks(v, 1, 3)[0].index,
            findSpatialPeak(v, SpatialPeakRefinement::kGaussian, 1, false).index);
  EXPECT_TRUE(findDistinctSpatialPeaks(v, 0, 3).empty());
  EXPECT_THROW(findDistinctSpatialPeaks(v, -1, 3), InvalidArgument);
  EXPECT_THROW(findDistinctSpatialPeaks(v, 2, -1), InvalidArgument);
}
