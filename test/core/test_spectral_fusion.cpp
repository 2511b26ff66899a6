/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Spectral fusion (paper IV-D) on degree bands and radial frequency shells (the robust
 * channel normalization that precedes it: test_normalize_channel.cpp).
 */
#include "channels/spectral_fusion.h"
#include "so3/so3_correlation.h"
#include "so3_test_support.h"
#include "support/error.h"

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

  EXPECT_THROW(sphericalBand(8, 8, 5), InvalidArgument);
  EXPECT_THROW(sphericalBand(-1, 8, 5), InvalidArgument);
  EXPECT_THROW(sphericalBand(0, 8, 0), InvalidArgument);
  EXPECT_THROW(normalizeChannel(Eigen::VectorXd::Ones(3), 0.0), InvalidArgument);
  EXPECT_THROW(normalizeChannel(Eigen::VectorXd::Ones(3),
                                std::numeric_limits<double>::quiet_NaN()),
               InvalidArgument);
}
