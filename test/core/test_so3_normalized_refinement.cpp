/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * evaluateCorrelations (several spectrum pairs sharing one Wigner recurrence) and the
 * energy-normalized Newton refinement (refineRotation with supports). Its effect on
 * tilted LiDAR pairs is tested with the simulator (test/simulator).
 */
#include "so3/so3_correlation.h"
#include "so3/so3_refinement.h"
#include "so3_test_support.h"
#include "support/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace pcl::phaser;

namespace {

constexpr double kDeg = M_PI / 180.0;

/** Samples of 8 weighted lobes over the whole sphere (f) and of the same lobes rotated
 *  back by \a rotation (h): f = h(rotation^-1 .). */
struct LobePair {
  Eigen::Matrix3d rotation;
  std::vector<double> f, h;
};

LobePair makeLobePair(int B, std::mt19937& rng)
{
  LobePair p;
  p.rotation = test::randomRotation(rng);
  std::vector<Eigen::Vector3d> src, tgt;
  std::vector<double> w;
  for (int i = 0; i < 8; ++i) {
    src.push_back(test::randomRotation(rng).col(0));
    tgt.push_back(p.rotation * src.back());
    w.push_back(1.0 + 0.3 * i);
  }
  p.f = test::lobeSamples(B, tgt, w, 0.6 * B);
  p.h = test::lobeSamples(B, src, w, 0.6 * B);
  return p;
}

TEST(So3NormalizedRefinement, SharedEvaluationEqualsSinglePairsBitForBit)
{
  std::mt19937 rng(31);
  const int B = 12;
  std::vector<SphericalSpectrum> F, H;
  for (int i = 0; i < 3; ++i) {
    F.push_back(test::randomSpectrum(B, rng));
    H.push_back(test::randomSpectrum(B, rng));
  }
  std::vector<Eigen::Matrix3d> rotations;
  for (int i = 0; i < 7; ++i)
    rotations.push_back(test::randomRotation(rng));
  rotations.push_back(Eigen::Matrix3d::Identity()); // beta = 0
  const std::vector<SpectrumPair> pairs = {
      {&F[0], &H[0]}, {&F[1], &H[1]}, {&F[2], &H[2]}};
  const auto one = evaluateCorrelations(pairs, rotations, 1);
  const auto two = evaluateCorrelations(pairs, rotations, 2);
  ASSERT_EQ(one.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(one[i], evaluateCorrelation(F[i], H[i], rotations, 1)) << "pair " << i;
    EXPECT_EQ(one[i], two[i]) << "pair " << i;
  }
  EXPECT_TRUE(evaluateCorrelations({}, rotations).empty());
}

TEST(So3NormalizedRefinement, RejectsIncompleteArguments)
{
  const SphericalSpectrum A = SphericalSpectrum::Zero(4, 4);
  const SphericalSpectrum C = SphericalSpectrum::Zero(3, 3);
  const std::vector<Eigen::Matrix3d> I = {Eigen::Matrix3d::Identity()};
  EXPECT_THROW(evaluateCorrelations({{&A, nullptr}}, I), InvalidArgument);
  EXPECT_THROW(evaluateCorrelations({{&A, &A}, {&A, &C}}, I), InvalidArgument);
  const SphericalSupport support{A, A};
  EXPECT_THROW(refineRotation(A, A, Eigen::Matrix3d::Identity(), 4, 3, 1, &support),
               InvalidArgument);
  EXPECT_THROW(refineRotation(A, A, Eigen::Matrix3d::Identity(), 4, 3, 1, nullptr,
                              nullptr, -1.0),
               InvalidArgument);
  EXPECT_THROW(refineRotation(A, A, Eigen::Matrix3d::Identity(), 4, 3, 1, nullptr,
                              nullptr, std::nan("")),
               InvalidArgument);
}

/** The trust region: from a start 2 grid cells from the maximum, the ascent stops on
 *  the boundary of the region (radius 0: the start itself); a region that holds the
 *  maximum changes nothing. */
TEST(So3NormalizedRefinement, TrustRegionBoundsTheStep)
{
  const int B = 16;
  std::mt19937 rng(9);
  const auto sht = SphericalHarmonicTransform::instance(B);
  const LobePair lobes = makeLobePair(B, rng);
  const Eigen::Matrix3d& R = lobes.rotation;
  const SphericalSpectrum F = sht->forward(lobes.f.data());
  const SphericalSpectrum H = sht->forward(lobes.h.data());
  const double cell = M_PI / (2 * B);
  const Eigen::Matrix3d start =
      Eigen::AngleAxisd(2.0 * cell, Eigen::Vector3d(3, -1, 2).normalized()) * R;
  const RefinedRotation free = refineRotation(F, H, start, B, 6, 1);
  EXPECT_LT(rotationDistance(free.rotation, R), 0.01 * kDeg);
  const RefinedRotation bounded =
      refineRotation(F, H, start, B, 6, 1, nullptr, nullptr, 0.5 * cell);
  EXPECT_LE(rotationDistance(bounded.rotation, start), 0.5 * cell * (1 + 1e-9));
  EXPECT_GT(rotationDistance(bounded.rotation, start), 0.4 * cell); // it did climb
  EXPECT_LT(rotationDistance(bounded.rotation, R), rotationDistance(start, R));
  const RefinedRotation fixed =
      refineRotation(F, H, start, B, 6, 1, nullptr, nullptr, 0.0);
  EXPECT_LT(rotationDistance(fixed.rotation, start), 1e-9);
  const RefinedRotation wide =
      refineRotation(F, H, start, B, 6, 1, nullptr, nullptr, 4.0 * cell);
  EXPECT_LT(rotationDistance(wide.rotation, R), 0.01 * kDeg);
}

/** Lobes over the whole sphere (every cell observed): the energy terms are then
 *  constant and the normalized refinement must find what the plain one finds. */
TEST(So3NormalizedRefinement, FullyObservedSignalsKeepTheExactRotation)
{
  const int B = 16;
  std::mt19937 rng(5);
  const auto sht = SphericalHarmonicTransform::instance(B);
  for (int trial = 0; trial < 3; ++trial) {
    const LobePair lobes = makeLobePair(B, rng);
    const Eigen::Matrix3d& R = lobes.rotation;
    const std::vector<double>&f = lobes.f, &h = lobes.h;
    std::vector<double> f2 = f, h2 = h, ones(f.size(), 1.0);
    for (std::size_t c = 0; c < f.size(); ++c) {
      f2[c] *= f[c];
      h2[c] *= h[c];
    }
    const SphericalSpectrum F = sht->forward(f.data()), H = sht->forward(h.data());
    const SphericalSupport sf{sht->forward(ones.data()), sht->forward(f2.data())};
    const SphericalSupport sh{sht->forward(ones.data()), sht->forward(h2.data())};
    // Start half a grid cell away, as after a grid search.
    const Eigen::Matrix3d start =
        Eigen::AngleAxisd(0.5 * M_PI / (2 * B), Eigen::Vector3d(1, 2, 3).normalized()) *
        R;
    const RefinedRotation plain = refineRotation(F, H, start, B, 3, 2);
    const RefinedRotation normalized = refineRotation(F, H, start, B, 3, 2, &sf, &sh);
    EXPECT_LT(rotationDistance(plain.rotation, R), 0.01 * kDeg);
    EXPECT_LT(rotationDistance(normalized.rotation, R), 0.01 * kDeg);
    EXPECT_EQ(plain.objective, plain.value);
    // value is the plain C at the result; the normalized objective is positive there.
    EXPECT_NEAR(normalized.value, evaluateCorrelation(F, H, {normalized.rotation})[0],
                1e-12 * std::abs(normalized.value));
    EXPECT_GT(normalized.objective, 0.0);
  }
}

} // namespace
