/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Spectral fusion (paper IV-D) on degree bands and radial frequency shells (the robust
 * channel normalization that precedes it: test_normalize_channel.cpp).
 */
#include "so3_test_support.h"

#include <pcl_phaser/core/error.h>
#include <pcl_phaser/core/so3_correlation.h>
#include <pcl_phaser/core/spatial_correlation.h>
#include <pcl_phaser/core/spectral_fusion.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>

using namespace pcl::phaser;

namespace {

using Complex = std::complex<double>;

/** Spectrum with |F(l,m)| = 1 and random phases (F(l,0) = +-1): degree energy 2l+1. */
SphericalSpectrum unitSpectrum(int B, std::mt19937& rng)
{
  std::uniform_real_distribution<double> phase(-M_PI, M_PI);
  SphericalSpectrum F = SphericalSpectrum::Zero(B, B);
  for (int l = 0; l < B; ++l) {
    F(l, 0) = phase(rng) < 0.0 ? -1.0 : 1.0;
    for (int m = 1; m <= l; ++m)
      F(l, m) = std::polar(1.0, phase(rng));
  }
  return F;
}

SpatialVolume randomVolume(const Eigen::Vector3i& dims, double voxel, std::mt19937& rng,
                           double sigma = 1.0)
{
  SpatialVolume v;
  v.grid.dims = dims;
  v.grid.voxel_size = voxel;
  v.values.assign(v.grid.size(), 0.0);
  if (sigma > 0.0) { // normal_distribution needs sigma > 0
    std::normal_distribution<double> n01(0.0, sigma);
    for (double& x : v.values)
      x = n01(rng);
  }
  return v;
}

/** Periodic 3-D box blur of half-width r per axis (a low-pass "scene-like" field). */
SpatialVolume blur(const SpatialVolume& in, int r)
{
  SpatialVolume out = in;
  const Eigen::Vector3i n = in.grid.dims;
  for (int axis = 0; axis < 3; ++axis) {
    const SpatialVolume src = out;
    for (int x = 0; x < n.x(); ++x)
      for (int y = 0; y < n.y(); ++y)
        for (int z = 0; z < n.z(); ++z) {
          double s = 0.0;
          for (int d = -r; d <= r; ++d) {
            Eigen::Vector3i q(x, y, z);
            q[axis] = (q[axis] + d + n[axis]) % n[axis];
            s += src.values[in.grid.flatIndex(q.x(), q.y(), q.z())];
          }
          out.values[in.grid.flatIndex(x, y, z)] = s / (2 * r + 1);
        }
  }
  return out;
}

/** Circular shift: out[x + s] = in[x]. */
SpatialVolume roll(const SpatialVolume& in, const Eigen::Vector3i& s)
{
  SpatialVolume out = in;
  const Eigen::Vector3i n = in.grid.dims;
  for (std::size_t i = 0; i < in.values.size(); ++i) {
    const Eigen::Vector3i p = in.grid.voxelIndex(i);
    const Eigen::Vector3i q = p + s + 4 * n; // non-negative before the modulo
    out.values[in.grid.flatIndex(q.x() % n.x(), q.y() % n.y(), q.z() % n.z())] =
        in.values[i];
  }
  return out;
}

/** Normalized real inner product of two half-spectra (multiplicity-weighted). */
double spectralCorrelation(const SpatialSpectrum& a, const SpatialSpectrum& b)
{
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (std::size_t i = 0; i < a.coefficients.size(); ++i) {
    const double w = a.multiplicity(i);
    ab += w * (a.coefficients[i] * std::conj(b.coefficients[i])).real();
    aa += w * std::norm(a.coefficients[i]);
    bb += w * std::norm(b.coefficients[i]);
  }
  return ab / std::sqrt(aa * bb);
}

double stddev(const Eigen::VectorXd& v)
{
  return std::sqrt((v.array() - v.mean()).square().mean());
}

} // namespace

// ---------------------------------------------------------------------------------------
TEST(SpectralFusion, BandEdgesAreDyadic)
{
  // B = 64, L = 5: [0,4) [4,8) [8,16) [16,32) [32,64).
  const int expected64[][2] = {{0, 0},  {3, 0},  {4, 1},  {7, 1},  {8, 2},
                               {15, 2}, {16, 3}, {31, 3}, {32, 4}, {63, 4}};
  for (const auto& e : expected64)
    EXPECT_EQ(sphericalBand(e[0], 64, 5), e[1]) << "degree " << e[0];
  // B = 75 (non-power of two): edges 4.6875, 9.375, 18.75, 37.5.
  const int expected75[][2] = {{4, 0},  {5, 1},  {9, 1},  {10, 2},
                               {18, 2}, {19, 3}, {37, 3}, {38, 4}};
  for (const auto& e : expected75)
    EXPECT_EQ(sphericalBand(e[0], 75, 5), e[1]) << "degree " << e[0];
  for (int l = 0; l < 16; ++l)
    EXPECT_EQ(sphericalBand(l, 16, 1), 0);

  // Spatial: voxel 0.5 m -> Nyquist 1 cycle/m; radial in cycles per meter.
  EXPECT_EQ(spatialBand({0.0, 0.0, 0.0}, 0.5, 5), 0);
  EXPECT_EQ(spatialBand({0.06, 0.0, 0.0}, 0.5, 5), 0);
  EXPECT_EQ(spatialBand({0.0, 0.0625, 0.0}, 0.5, 5), 1);
  EXPECT_EQ(spatialBand({0.0, -0.3, 0.3}, 0.5, 5), 3); // |f| = 0.424
  EXPECT_EQ(spatialBand({0.0, 0.0, 0.5}, 0.5, 5), 4);
  EXPECT_EQ(spatialBand({1.0, -1.0, 1.0}, 0.5, 5), 4); // corner beyond Nyquist

  // Every coefficient of an anisotropic grid: the choice is -1 exactly inside the
  // averaged sphere |f| < f_max / 16, whatever the axis.
  std::mt19937 rng(3);
  const SpatialSpectrum S = computeSpectrum(randomVolume({48, 40, 32}, 0.5, rng));
  const std::vector<int> choice = selectSpatialChannels({S, S});
  int averaged = 0;
  for (std::size_t i = 0; i < S.coefficients.size(); ++i) {
    const bool inside = S.frequency(i).norm() < 1.0 / 16.0;
    EXPECT_EQ(choice[i] < 0, inside) << "coefficient " << i;
    averaged += inside;
  }
  EXPECT_GT(averaged, 1);
}

TEST(SpectralFusion, IdenticalChannelsFuseToThatChannelExactly)
{
  std::mt19937 rng(5);
  const SphericalSpectrum F = test::randomSpectrum(24, rng);
  for (int levels : {1, 3, 5})
    for (int K : {1, 2, 3, 4}) {
      FusionParameters p;
      p.levels = levels;
      const std::vector<SphericalSpectrum> channels(K, F);
      EXPECT_TRUE(fuseSpherical(channels, p) == F) << "L " << levels << " K " << K;
    }

  const SpatialSpectrum S = computeSpectrum(randomVolume({20, 18, 11}, 0.3, rng));
  for (int K : {1, 3}) {
    const SpatialSpectrum fused = fuseSpatial(std::vector<SpatialSpectrum>(K, S));
    EXPECT_TRUE(fused.coefficients == S.coefficients && fused.grid.dims == S.grid.dims);
  }
}

TEST(SpectralFusion, SphericalPicksDominantChannelPerBandAndAveragesTopLevel)
{
  // B = 32, L = 5: bands [0,2) [2,4) [4,8) [8,16) [16,32). A is 100x stronger below
  // degree 8, B 100x stronger from degree 8 on.
  const int B = 32;
  std::mt19937 rng(11);
  SphericalSpectrum A = unitSpectrum(B, rng), Bs = unitSpectrum(B, rng);
  for (int l = 0; l < B; ++l) {
    A.row(l) *= l < 8 ? 10.0 : 0.1;
    Bs.row(l) *= l < 8 ? 0.1 : 10.0;
  }
  // Radius 0 and 1 keep every degree right; a wider window would let the strong side
  // reach across the octave edge at degree 8 (that is what a window does).
  for (int radius : {0, 1}) {
    FusionParameters p;
    p.degree_radius = radius;
    const SphericalSpectrum fused = fuseSpherical({A, Bs}, p);
    const std::vector<int> choice = selectSphericalChannels({A, Bs}, p);
    for (int l = 0; l < B; ++l) {
      const int want = l < 2 ? -1 : (l < 8 ? 0 : 1);
      EXPECT_EQ(choice[l], want) << "radius " << radius << " degree " << l;
      for (int m = 0; m <= l; ++m) {
        const Complex expect =
            l < 2 ? 0.5 * (A(l, m) + Bs(l, m)) : (l < 8 ? A : Bs)(l, m);
        EXPECT_LT(std::abs(fused(l, m) - expect), 1e-14) << l << " " << m;
      }
    }
    EXPECT_EQ(fused(5, 0).imag(), 0.0); // still a real function's spectrum
  }
}

TEST(SpectralFusion, SpatialPicksDominantChannelPerShellAndAveragesTopLevel)
{
  // Spectra built directly: A 100x stronger in bands 1-2, B in bands 3-4.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> phase(-M_PI, M_PI);
  SpatialSpectrum A, B;
  A.grid.dims = {48, 40, 32};
  A.grid.voxel_size = 0.5;
  A.coefficients.resize(48 * 40 * 17);
  B = A;
  std::vector<int> band(A.coefficients.size());
  std::set<int> seen;
  for (std::size_t i = 0; i < A.coefficients.size(); ++i) {
    band[i] = spatialBand(A.frequency(i), 0.5, 5);
    seen.insert(band[i]);
    const double a = band[i] <= 2 ? 10.0 : 0.1;
    A.coefficients[i] = std::polar(a, phase(rng));
    B.coefficients[i] = std::polar(1.0 / a, phase(rng));
  }
  EXPECT_EQ(seen.size(), 5u); // every band is populated
  const SpatialSpectrum fused = fuseSpatial({A, B});
  const std::vector<int> choice = selectSpatialChannels({A, B});
  for (std::size_t i = 0; i < A.coefficients.size(); ++i) {
    const int want = band[i] == 0 ? -1 : (band[i] <= 2 ? 0 : 1);
    ASSERT_EQ(choice[i], want) << "coefficient " << i;
    const Complex expect = want < 0 ? 0.5 * (A.coefficients[i] + B.coefficients[i])
                                    : (want == 0 ? A : B).coefficients[i];
    ASSERT_LT(std::abs(fused.coefficients[i] - expect), 1e-14) << i;
  }
}

TEST(SpectralFusion, SphericalSelectionCommutesWithRotation)
{
  // Three channels with random per-degree scales, so different channels win different
  // degrees; B = 16, L = 4: bands [0,2) [2,4) [4,8) [8,16).
  const int B = 16;
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> logscale(std::log(0.3), std::log(3.0));
  std::vector<SphericalSpectrum> channels;
  for (int c = 0; c < 3; ++c) {
    SphericalSpectrum F = test::randomSpectrum(B, rng);
    for (int l = 0; l < B; ++l)
      F.row(l) *= std::exp(logscale(rng));
    channels.push_back(F);
  }
  const auto rotateAll = [](std::vector<SphericalSpectrum> ch,
                            const Eigen::Matrix3d& R) {
    for (SphericalSpectrum& F : ch)
      F = test::rotateSpectrum(F, R);
    return ch;
  };
  for (int radius : {0, 1}) {
    FusionParameters p;
    p.levels = 4;
    p.degree_radius = radius;
    const std::vector<int> choice = selectSphericalChannels(channels, p);
    const std::set<int> winners(choice.begin() + 2, choice.end());
    EXPECT_GE(winners.size(), 2u) << "selection must not be trivial";
    const SphericalSpectrum fused = fuseSpherical(channels, p);
    for (int trial = 0; trial < 3; ++trial) {
      const Eigen::Matrix3d R = test::randomRotation(rng);
      const std::vector<SphericalSpectrum> rotated = rotateAll(channels, R);
      EXPECT_EQ(selectSphericalChannels(rotated, p), choice);
      EXPECT_LT((fuseSpherical(rotated, p) - test::rotateSpectrum(fused, R))
                    .cwiseAbs()
                    .maxCoeff(),
                1e-12)
          << "radius " << radius << " trial " << trial;
    }
  }

  // Control: the same test catches a per-(l, m) selection (what a rule on single
  // coefficients would do), because |F(l, m)| changes under rotation.
  const auto perCoefficient = [&](const std::vector<SphericalSpectrum>& ch) {
    SphericalSpectrum out = ch[0];
    for (int c = 1; c < 3; ++c)
      out = (ch[c].array().abs() > out.array().abs()).select(ch[c], out);
    return out;
  };
  const Eigen::Matrix3d R = test::randomRotation(rng);
  const SphericalSpectrum expect = test::rotateSpectrum(perCoefficient(channels), R);
  EXPECT_GT((perCoefficient(rotateAll(channels, R)) - expect).cwiseAbs().maxCoeff(),
            1e-3);
}

TEST(SpectralFusion, SpatialSelectionIsTranslationInvariant)
{
  // A smooth field (wins low shells), white noise (wins high shells), a mix.
  std::mt19937 rng(19);
  const Eigen::Vector3i dims(24, 20, 16);
  const SpatialVolume smooth = blur(randomVolume(dims, 0.4, rng, 3.0), 2);
  const SpatialVolume white = randomVolume(dims, 0.4, rng, 0.5);
  const SpatialVolume mix = blur(randomVolume(dims, 0.4, rng), 1);
  const Eigen::Vector3i shift(5, -3, 7);
  std::vector<SpatialSpectrum> channels, shifted;
  for (const SpatialVolume* v : {&smooth, &white, &mix}) {
    channels.push_back(computeSpectrum(*v));
    shifted.push_back(computeSpectrum(roll(*v, shift)));
  }
  const std::vector<int> choice = selectSpatialChannels(channels);
  EXPECT_EQ(selectSpatialChannels(shifted), choice);
  const std::set<int> winners(choice.begin(), choice.end());
  EXPECT_GE(winners.size(), 3u) << "averaged band and at least two winners";

  const SpatialSpectrum fused = fuseSpatial(channels);
  const SpatialSpectrum fused_shifted = fuseSpatial(shifted);
  double tolerance = 0.0;
  for (const Complex& c : fused.coefficients)
    tolerance = std::max(tolerance, 1e-12 * std::abs(c));
  double worst = 0.0;
  for (std::size_t i = 0; i < fused.coefficients.size(); ++i) {
    // g[x] = f[x - s]  <=>  G[k] = F[k] exp(-2 pi i k.s / n).
    const Eigen::Vector3d k = fused.frequencyIndex(i).cast<double>();
    const double angle =
        -2.0 * M_PI *
        (k.array() * shift.cast<double>().array() / dims.cast<double>().array()).sum();
    worst = std::max(worst, std::abs(fused_shifted.coefficients[i] -
                                     fused.coefficients[i] * std::polar(1.0, angle)));
  }
  EXPECT_LT(worst, tolerance);

  // The fused half-spectrum stays Hermitian on the kz = 0 and kz = nz/2 planes.
  const auto at = [&](int ix, int iy, int kz) {
    const int nx = dims.x(), ny = dims.y();
    return fused
        .coefficients[(((ix + nx) % nx) * ny + (iy + ny) % ny) * fused.halfZ() + kz];
  };
  for (int kz : {0, dims.z() / 2})
    for (int ix = 0; ix < dims.x(); ++ix)
      for (int iy = 0; iy < dims.y(); ++iy)
        EXPECT_LT(std::abs(at(ix, iy, kz) - std::conj(at(-ix, -iy, kz))), tolerance);

  // Thread count does not change the result.
  FusionParameters p;
  p.num_threads = 4;
  EXPECT_TRUE(fuseSpatial(channels, p).coefficients == fused.coefficients);
}

TEST(SpectralFusion, NoiseChannelDoesNotDegradeSpatialCorrelation)
{
  // Clean scene: 150 blurred point blobs (decaying spectrum). Noise: white, drawn
  // independently for target and source, at an RMS of `level` times the clean
  // channel's. Measured: the lag of the fused correlation peak, its peak-to-sidelobe
  // score against the clean-only score, and the normalized spectral correlation of the
  // fused target with the clean target.
  // Tolerances: at half the RMS the peak is exact, >= 60 % of the score is kept
  // (measured 79-83 % over 10 scenes) and the fused spectrum correlates > 0.85 with the
  // clean one (measured 0.884-0.888); at equal RMS (what normalizeChannel gives a
  // pure-noise channel) the peak is still exact with >= 25 % of the score (measured
  // 34-41 %; plain averaging, levels = 1, keeps 44-51 %).
  std::mt19937 rng(23);
  const Eigen::Vector3i dims(32, 32, 16);
  SpatialVolume sparse = randomVolume(dims, 0.5, rng, 0.0);
  std::uniform_int_distribution<std::size_t> pick(0, sparse.values.size() - 1);
  for (int i = 0; i < 150; ++i)
    sparse.values[pick(rng)] = 1.0;
  const SpatialVolume source = blur(sparse, 1);
  const Eigen::Vector3i shift(4, -6, 3);
  const SpatialVolume target = roll(source, shift);
  const Eigen::Map<const Eigen::VectorXd> values(target.values.data(),
                                                 target.values.size());
  const double sigma = stddev(values);

  const SpatialSpectrum T = computeSpectrum(target), S = computeSpectrum(source);
  const SpatialCorrelationResult clean = correlateSpatial(T, S);
  ASSERT_EQ(Eigen::Vector3i(clean.lag.array().round().cast<int>()), shift);
  for (const double level : {0.5, 1.0}) {
    const SpatialSpectrum Tn =
        computeSpectrum(randomVolume(dims, 0.5, rng, level * sigma));
    const SpatialSpectrum Sn =
        computeSpectrum(randomVolume(dims, 0.5, rng, level * sigma));
    const SpatialSpectrum Tf = fuseSpatial({T, Tn}), Sf = fuseSpatial({S, Sn});
    const SpatialCorrelationResult fused = correlateSpatial(Tf, Sf);
    EXPECT_EQ(Eigen::Vector3i(fused.lag.array().round().cast<int>()), shift) << level;
    EXPECT_GT(fused.score, (level < 1.0 ? 0.6 : 0.25) * clean.score)
        << "noise " << level << ": fused " << fused.score << " clean " << clean.score;
    if (level < 1.0) {
      EXPECT_GT(spectralCorrelation(Tf, T), 0.85);
    }
  }
}

TEST(SpectralFusion, NoiseChannelDoesNotDegradeRotationPeak)
{
  // Clean: 8 lobes (mean removed, as the spherical sampler does), source and rotated
  // target. Noise: white on the sphere, at half the clean channel's RMS, independent
  // for target and source. Measured: the SO(3) grid argmax of the fused spectra is
  // within one grid step (pi / B) of the true rotation. (At equal RMS the max-energy
  // rule, like plain averaging, loses the peak in about half of the scenes at B = 32:
  // noise wins the high degrees where smooth lobes are weak.)
  const int B = 16;
  std::mt19937 rng(29);
  const auto sht = SphericalHarmonicTransform::instance(B);
  const auto corr = So3Correlator::instance(B);
  for (int trial = 0; trial < 4; ++trial) {
    const Eigen::Matrix3d R = test::randomRotation(rng);
    std::vector<Eigen::Vector3d> src, tgt;
    std::vector<double> w;
    for (int i = 0; i < 8; ++i) {
      src.push_back(test::randomRotation(rng).col(0));
      tgt.push_back(R * src.back());
      w.push_back(1.0 + 0.3 * i);
    }
    SphericalSpectrum F = sht->forward(test::lobeSamples(B, tgt, w, 0.6 * B).data());
    SphericalSpectrum H = sht->forward(test::lobeSamples(B, src, w, 0.6 * B).data());
    F(0, 0) = H(0, 0) = 0.0;
    const auto noise = [&] {
      SphericalSpectrum N = test::randomSpectrum(B, rng);
      N(0, 0) = 0.0;
      return SphericalSpectrum(
          N * (0.5 * std::sqrt(spectrumSquaredNorm(F) / spectrumSquaredNorm(N))));
    };
    const So3GridIndex clean = corr->correlate(F, H).argmax();
    ASSERT_LT(rotationDistance(rotationFromEuler(gridEuler(clean, B)), R), M_PI / B);
    const SphericalSpectrum Ff = fuseSpherical({F, noise()});
    const SphericalSpectrum Hf = fuseSpherical({H, noise()});
    const So3GridIndex fused = corr->correlate(Ff, Hf).argmax();
    EXPECT_LT(rotationDistance(rotationFromEuler(gridEuler(fused, B)), R), M_PI / B)
        << "trial " << trial;
  }
}

TEST(SpectralFusion, AllZeroChannelsAreLeftOut)
{
  // A missing field (all zero) must not halve the averaged band.
  std::mt19937 rng(41);
  const SphericalSpectrum F = test::randomSpectrum(16, rng);
  const SphericalSpectrum G = test::randomSpectrum(16, rng);
  const SphericalSpectrum Z = SphericalSpectrum::Zero(16, 16);
  EXPECT_TRUE(fuseSpherical({Z, F, Z}) == F);
  EXPECT_TRUE(fuseSpherical({F, Z, G}) == fuseSpherical({F, G}));
  std::vector<int> choice = selectSphericalChannels({Z, F, G});
  for (int& c : choice) // indices refer to the caller's channel list
    EXPECT_TRUE(c == -1 || c == 1 || c == 2);
  EXPECT_TRUE(fuseSpherical({Z, Z}) == Z);

  const SpatialSpectrum S = computeSpectrum(randomVolume({12, 10, 8}, 0.5, rng));
  const SpatialSpectrum T = computeSpectrum(randomVolume({12, 10, 8}, 0.5, rng));
  SpatialSpectrum zero = S;
  std::fill(zero.coefficients.begin(), zero.coefficients.end(), Complex(0.0));
  EXPECT_TRUE(fuseSpatial({zero, S}).coefficients == S.coefficients);
  EXPECT_TRUE(fuseSpatial({S, zero, T}).coefficients ==
              fuseSpatial({S, T}).coefficients);
  for (int c : selectSpatialChannels({zero, S, T}))
    EXPECT_NE(c, 0);
}

TEST(SpectralFusion, BadInputThrows)
{
  std::mt19937 rng(37);
  const SphericalSpectrum F = test::randomSpectrum(8, rng);
  EXPECT_THROW(fuseSpherical({}), InvalidArgument);
  EXPECT_THROW(fuseSpherical({F, test::randomSpectrum(9, rng)}), InvalidArgument);
  EXPECT_THROW(fuseSpherical({SphericalSpectrum::Zero(8, 7)}), InvalidArgument);
  FusionParameters bad;
  bad.levels = 0;
  EXPECT_THROW(fuseSpherical({F}, bad), InvalidArgument);
  EXPECT_THROW(selectSphericalChannels({F}, bad), InvalidArgument);
  FusionParameters radius;
  radius.degree_radius = -1;
  EXPECT_THROW(fuseSpherical({F, F}, radius), InvalidArgument);

  const SpatialSpectrum S = computeSpectrum(randomVolume({8, 6, 4}, 0.5, rng));
  EXPECT_THROW(fuseSpatial({}), InvalidArgument);
  EXPECT_THROW(fuseSpatial({S}, bad), InvalidArgument);
  std::vector<SpatialSpectrum> others(4, S); // different dims, voxel, origin, size
  others[0] = computeSpectrum(randomVolume({8, 6, 6}, 0.5, rng));
  others[1].grid.voxel_size = 0.25;
  others[2].grid.origin.x() += 1.0;
  others[3].coefficients.pop_back();
  for (const SpatialSpectrum& other : others)
    EXPECT_THROW(fuseSpatial({S, other}), InvalidArgument);
  EXPECT_THROW(fuseSpatial({others[3]}), InvalidArgument);
  FusionParameters threads;
  threads.num_threads = -1;
  EXPECT_THROW(fuseSpatial({S, S}, threads), InvalidArgument);

  EXPECT_THROW(sphericalBand(8, 8, 5), InvalidArgument);
  EXPECT_THROW(sphericalBand(-1, 8, 5), InvalidArgument);
  EXPECT_THROW(sphericalBand(0, 8, 0), InvalidArgument);
  EXPECT_THROW(spatialBand({0.1, 0, 0}, 0.0, 5), InvalidArgument);
  EXPECT_THROW(spatialBand({0.1, 0, 0}, 0.5, 0), InvalidArgument);
  EXPECT_THROW(normalizeChannel(Eigen::VectorXd::Ones(3), 0.0), InvalidArgument);
  EXPECT_THROW(normalizeChannel(Eigen::VectorXd::Ones(3),
                                std::numeric_limits<double>::quiet_NaN()),
               InvalidArgument);
}
