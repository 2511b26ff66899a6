/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Spec section 4.1 items 6-9: exact correlation, fast path = reference path, rotation
 * recovery with refinement (poles included), swapped inputs, zero padding.
 */
#include "so3/so3_correlation.h"
#include "so3/so3_refinement.h"
#include "so3_test_support.h"
#include "sphere/spherical_grid.h"
#include "support/error.h"
#include "uncertainty/peak_neighborhood.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <thread>

using namespace pcl::phaser;

namespace {

double maxAbs(const std::vector<double>& v)
{
  double m = 0.0;
  for (double x : v)
    m = std::max(m, std::abs(x));
  return m;
}

/** Rotation found by grid argmax + Newton refinement for target = R source (lobes). */
struct Recovered {
  Eigen::Matrix3d grid, refined;
};

Recovered recoverLobes(const Eigen::Matrix3d& R_true, int B, bool swap_inputs = false)
{
  std::mt19937 rng(99);
  std::vector<Eigen::Vector3d> src, tgt;
  std::vector<double> w;
  for (int i = 0; i < 8; ++i) { // 8 lobes: every rotation axis well constrained
    src.push_back(test::randomRotation(rng).col(0));
    tgt.push_back(R_true * src.back());
    w.push_back(1.0 + 0.3 * i);
  }
  const double kappa = 0.6 * B;
  const auto sht = SphericalHarmonicTransform::instance(B);
  SphericalSpectrum F = sht->forward(test::lobeSamples(B, tgt, w, kappa).data());
  SphericalSpectrum H = sht->forward(test::lobeSamples(B, src, w, kappa).data());
  if (swap_inputs)
    std::swap(F, H);
  const auto corr = So3Correlator::instance(B);
  const So3CorrelationGrid C = corr->correlate(F, H, 2);
  Recovered r;
  r.grid = rotationFromEuler(gridEuler(C.argmax(), B));
  r.refined = refineRotation(F, H, r.grid, B, 3, 2).rotation;
  return r;
}

constexpr double kDeg = M_PI / 180.0;

} // namespace

TEST(So3Correlation, FastPathEqualsReferencePath)
{
  std::mt19937 rng(1);
  for (int B : {1, 2, 3, 5, 8, 16})
    for (int Bo : {B, 2 * B}) {
      const SphericalSpectrum F = test::randomSpectrum(B, rng);
      const SphericalSpectrum H = test::randomSpectrum(B, rng);
      const std::vector<double> ref = test::referenceCorrelation(F, H, Bo);
      const So3CorrelationGrid C = So3Correlator(B, Bo).correlate(F, H, 2);
      const int N = 2 * Bo;
      double worst = 0.0;
      for (int j = 0; j < N; ++j)
        for (int a = 0; a < N; ++a)
          for (int c = 0; c < N; ++c)
            worst = std::max(worst, std::abs(C(j, a, c) - ref[(j * N + a) * N + c]));
      EXPECT_LT(worst, 1e-12 * maxAbs(ref)) << "B=" << B << " Bo=" << Bo;
    }
}

TEST(So3Correlation, ExactAtGridRotations)
{
  std::mt19937 rng(2);
  const int B = 8, N = 2 * B;
  const SphericalSpectrum H = test::randomSpectrum(B, rng);
  const double norm2 = spectrumSquaredNorm(H);
  const auto sht = SphericalHarmonicTransform::instance(B);
  const std::vector<double> h = sht->inverse(H);
  for (const So3GridIndex& idx :
       {So3GridIndex{3, 5, 11}, So3GridIndex{0, 0, 0}, So3GridIndex{N - 1, N - 1, 2}}) {
    const Eigen::Matrix3d R0 = rotationFromEuler(gridEuler(idx, B));
    const SphericalSpectrum F = test::rotateSpectrum(H, R0);
    const So3CorrelationGrid C = So3Correlator::instance(B)->correlate(F, H);
    const So3GridIndex best = C.argmax();
    EXPECT_EQ(best.beta, idx.beta);
    EXPECT_EQ(best.alpha, idx.alpha);
    EXPECT_EQ(best.gamma, idx.gamma);
    EXPECT_NEAR(C(idx), norm2, 1e-12 * norm2);
    // Other grid points: brute-force S^2 quadrature of f(w) h(R^-1 w), exact for degree
    // < 2B.
    const std::vector<double> f = sht->inverse(F);
    const std::vector<double> wq = quadratureWeights(B);
    for (const So3GridIndex& other :
         {So3GridIndex{1, 2, 3}, So3GridIndex{N - 2, 7, 0}}) {
      const Eigen::Matrix3d R = rotationFromEuler(gridEuler(other, B));
      double integral = 0.0;
      for (int j = 0; j < N; ++j)
        for (int k = 0; k < N; ++k)
          integral += wq[j] * f[j * N + k] *
                      test::synthesize(H, R.transpose() * sampleDirection(j, k, B));
      integral *= M_PI / B;
      EXPECT_NEAR(C(other), integral, 1e-12 * norm2);
    }
  }
}

TEST(So3Correlation, ArgmaxNearIdentityIgnoresFartherPeaks)
{
  // F holds H rotated slightly and, twice as strong, H rotated by about 90 deg: the
  // global maximum is the far copy, the search near the identity finds the near one.
  std::mt19937 rng(5);
  const int B = 8, N = 2 * B;
  const SphericalSpectrum H = test::randomSpectrum(B, rng);
  const So3GridIndex near_index{0, 1, N - 1}, far_index{N / 2, 3, 7};
  const SphericalSpectrum near_copy =
      test::rotateSpectrum(H, rotationFromEuler(gridEuler(near_index, B)));
  const SphericalSpectrum far_copy =
      test::rotateSpectrum(H, rotationFromEuler(gridEuler(far_index, B)));
  const SphericalSpectrum F = near_copy + 2.0 * far_copy;
  const So3CorrelationGrid C = So3Correlator::instance(B)->correlate(F, H);
  const So3GridIndex global = C.argmax();
  EXPECT_EQ(global.beta, far_index.beta);
  const double radius = 10.0 * M_PI / 180.0;
  const So3GridIndex local = C.argmaxNearIdentity(radius);
  // Brute force over the whole grid.
  double best = -1e300;
  So3GridIndex expected{};
  for (int j = 0; j < N; ++j)
    for (int a = 0; a < N; ++a)
      for (int c = 0; c < N; ++c) {
        const So3GridIndex i{j, a, c};
        const double angle = rotationDistance(rotationFromEuler(gridEuler(i, B)),
                                              Eigen::Matrix3d::Identity());
        if (angle <= radius && C(i) > best) {
          best = C(i);
          expected = i;
        }
      }
  EXPECT_EQ(local.beta, expected.beta);
  EXPECT_EQ(local.alpha, expected.alpha);
  EXPECT_EQ(local.gamma, expected.gamma);
  EXPECT_LE(rotationDistance(rotationFromEuler(gridEuler(local, B)),
                             Eigen::Matrix3d::Identity()),
            radius);
  // No sample within the radius: the sample nearest the identity (beta_0 = pi / 4B).
  const So3GridIndex nearest = C.argmaxNearIdentity(0.0);
  EXPECT_NEAR(rotationDistance(rotationFromEuler(gridEuler(nearest, B)),
                               Eigen::Matrix3d::Identity()),
              M_PI / (4 * B), 1e-9);
}

TEST(So3Correlation, ZeroPaddingEqualsDirectEvaluation)
{
  std::mt19937 rng(4);
  const int B = 6;
  const SphericalSpectrum F = test::randomSpectrum(B, rng);
  const SphericalSpectrum H = test::randomSpectrum(B, rng);
  for (int Bo : {2 * B, 3 * B}) {
    const So3CorrelationGrid C = So3Correlator(B, Bo).correlate(F, H);
    std::vector<Eigen::Matrix3d> rotations;
    std::vector<double> grid_values;
    for (int i = 0; i < 40; ++i) {
      const So3GridIndex idx{(i * 7) % (2 * Bo), (i * 13) % (2 * Bo),
                             (i * 5 + 3) % (2 * Bo)};
      rotations.push_back(rotationFromEuler(gridEuler(idx, Bo)));
      grid_values.push_back(C(idx));
    }
    const std::vector<double> direct = evaluateCorrelation(F, H, rotations, 2);
    for (std::size_t i = 0; i < direct.size(); ++i)
      EXPECT_NEAR(grid_values[i], direct[i], 1e-13 * maxAbs(direct)) << "Bo=" << Bo;
  }
}

TEST(So3Correlation, RecoversRandomRotationsWithRefinement)
{
  const int B = 16;
  std::mt19937 rng(2024);
  std::vector<Eigen::Matrix3d> cases = {
      Eigen::Matrix3d::Identity(),
      rotationFromEuler({0.7, 0.0, -1.1}),        // beta = 0
      rotationFromEuler({-2.0, 0.02, 0.4}),       // beta near 0
      rotationFromEuler({1.3, M_PI - 0.03, 2.2}), // beta near pi
      rotationFromEuler({0.3, M_PI, 0.0}),        // beta = pi
  };
  for (int i = 0; i < 8; ++i)
    cases.push_back(test::randomRotation(rng));
  for (const Eigen::Matrix3d& R : cases) {
    const Recovered r = recoverLobes(R, B);
    // The spec's 1.3 pi/(2Bo) is the distance to the *nearest* grid point; the argmax
    // of an anisotropic peak may be the next one, hence 1.5.
    EXPECT_LT(rotationDistance(r.grid, R), 1.5 * M_PI / (2 * B));
    EXPECT_LT(rotationDistance(r.refined, R), 0.01 * kDeg)
        << "euler beta " << eulerFromRotation(R).beta;
  }
}

TEST(So3Correlation, SwappedInputsGiveTranspose)
{
  std::mt19937 rng(77);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const Recovered r = recoverLobes(R, 16, /*swap_inputs=*/true);
    EXPECT_LT(rotationDistance(r.refined, R.transpose()), 0.01 * kDeg);
    EXPECT_GT(rotationDistance(r.refined, R), 1.0 * kDeg); // not accidentally symmetric
  }
}

TEST(So3Correlation, ThreadCountDoesNotChangeBits)
{
  std::mt19937 rng(8);
  const int B = 24, Bo = 30;
  const SphericalSpectrum F = test::randomSpectrum(B, rng);
  const SphericalSpectrum H = test::randomSpectrum(B, rng);
  const auto corr = So3Correlator::instance(B, Bo);
  const So3CorrelationGrid a = corr->correlate(F, H, 1);
  const So3CorrelationGrid b = corr->correlate(F, H, 2);
  const So3CorrelationGrid c = corr->correlate(F, H, 3);
  const int N = 2 * Bo;
  bool same = true;
  for (int j = 0; j < N; ++j)
    for (int al = 0; al < N; ++al)
      for (int g = 0; g < N; ++g)
        same = same && a(j, al, g) == b(j, al, g) && a(j, al, g) == c(j, al, g);
  EXPECT_TRUE(same);
  std::vector<Eigen::Matrix3d> rots = {test::randomRotation(rng),
                                       test::randomRotation(rng)};
  EXPECT_EQ(evaluateCorrelation(F, H, rots, 1), evaluateCorrelation(F, H, rots, 2));
}

TEST(So3Correlation, ThreadCountDoesNotChangeBitsAtWorkingBandwidth)
{
  // B = 64 is split over the threads (smaller bandwidths run on one); 6 beta rows keep
  // the test short. The peak searches over the 128^3 grid are split too.
  std::mt19937 rng(9);
  const int B = 64, rows = 6;
  const SphericalSpectrum F = test::randomSpectrum(B, rng);
  const SphericalSpectrum H = test::randomSpectrum(B, rng);
  const auto corr = So3Correlator::instance(B);
  const So3CorrelationGrid a = corr->correlate(F, H, 1, rows);
  const So3CorrelationGrid b = corr->correlate(F, H, 2, rows);
  const int N = a.size();
  bool same = true;
  for (int j = 0; j < rows; ++j)
    for (int al = 0; al < N; ++al)
      for (int g = 0; g < N; ++g)
        same = same && a(j, al, g) == b(j, al, g);
  EXPECT_TRUE(same);
  const So3GridIndex m1 = a.argmax(1), m2 = a.argmax(2);
  EXPECT_EQ(m1.beta, m2.beta);
  EXPECT_EQ(m1.alpha, m2.alpha);
  EXPECT_EQ(m1.gamma, m2.gamma);
  const std::vector<So3GridIndex> p1 = distinctPeaks(a, 5, 0.1, 1);
  const std::vector<So3GridIndex> p2 = distinctPeaks(a, 5, 0.1, 2);
  ASSERT_EQ(p1.size(), p2.size());
  ASSERT_FALSE(p1.empty());
  for (std::size_t i = 0; i < p1.size(); ++i)
    EXPECT_TRUE(p1[i].beta == p2[i].beta && p1[i].alpha == p2[i].alpha &&
                p1[i].gamma == p2[i].gamma);
}

TEST(So3Correlation, ConcurrentCorrelationsAgree)
{
  std::mt19937 rng(9);
  const int B = 16;
  const SphericalSpectrum F = test::randomSpectrum(B, rng);
  const SphericalSpectrum H = test::randomSpectrum(B, rng);
  const auto corr = So3Correlator::instance(B);
  const So3GridIndex expected = corr->correlate(F, H).argmax();
  std::vector<So3GridIndex> got(4);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back(
        [&, t] { got[t] = So3Correlator::instance(B)->correlate(F, H, 1).argmax(); });
  for (std::thread& t : threads)
    t.join();
  for (const So3GridIndex& g : got) {
    EXPECT_EQ(g.beta, expected.beta);
    EXPECT_EQ(g.alpha, expected.alpha);
    EXPECT_EQ(g.gamma, expected.gamma);
  }
}

TEST(So3Correlation, RejectsIllegalArguments)
{
  EXPECT_THROW(So3Correlator::instance(0), InvalidArgument);
  EXPECT_THROW(So3Correlator::instance(257), InvalidArgument);
  EXPECT_THROW(So3Correlator(8, 4), InvalidArgument);
  EXPECT_THROW(So3Correlator(8, 300), InvalidArgument);
  const auto corr = So3Correlator::instance(4);
  EXPECT_THROW(
      corr->correlate(SphericalSpectrum::Zero(4, 4), SphericalSpectrum::Zero(5, 5)),
      InvalidArgument);
  EXPECT_THROW(evaluateCorrelation(SphericalSpectrum::Zero(4, 4),
                                   SphericalSpectrum::Zero(3, 3),
                                   {Eigen::Matrix3d::Identity()}),
               InvalidArgument);
}

TEST(So3Correlation, BandwidthOneIsConstant)
{
  SphericalSpectrum F(1, 1), H(1, 1);
  F(0, 0) = 2.0;
  H(0, 0) = 3.0;
  const So3CorrelationGrid C = So3Correlator(1, 1).correlate(F, H);
  for (int j = 0; j < 2; ++j)
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 2; ++c)
        EXPECT_NEAR(C(j, a, c), 6.0, 1e-14);
}

TEST(So3Correlation, TiltLimitedGridEqualsFullRows)
{
  std::mt19937 rng(5);
  const int B = 16, N = 2 * B;
  const SphericalSpectrum F = test::randomSpectrum(B, rng);
  const SphericalSpectrum H = test::randomSpectrum(B, rng);
  const auto corr = So3Correlator::instance(B);
  const So3CorrelationGrid full = corr->correlate(F, H, 2);
  const int rows = betaRowsForTilt(B, 20.0 * kDeg);
  // beta_j = (2j + 1) 180 / (4 B) deg: rows 0..3 are within 20 deg, plus one more.
  EXPECT_EQ(rows, 5);
  const So3CorrelationGrid part = corr->correlate(F, H, 2, rows);
  EXPECT_EQ(part.betaRows(), rows);
  double worst = 0.0, scale = 0.0;
  for (int j = 0; j < N; ++j)
    for (int a = 0; a < N; ++a)
      for (int c = 0; c < N; ++c) {
        scale = std::max(scale, std::abs(full(j, a, c)));
        if (j < rows)
          worst = std::max(worst, std::abs(part(j, a, c) - full(j, a, c)));
        else
          EXPECT_EQ(part(j, a, c), -std::numeric_limits<double>::infinity());
      }
  EXPECT_LT(worst, 1e-12 * scale);
  // The argmax stays inside the rows whose neighbors were computed, and is the best
  // of them on the full grid.
  const So3GridIndex best = part.argmax(2);
  EXPECT_LT(best.beta, rows - 1);
  for (int j = 0; j < rows - 1; ++j)
    for (int a = 0; a < N; ++a)
      for (int c = 0; c < N; ++c)
        EXPECT_LE(full(j, a, c), full(best) + 1e-12 * scale);
  EXPECT_EQ(part.argmax(1).alpha, best.alpha);
  EXPECT_EQ(part.argmax(1).gamma, best.gamma);
  EXPECT_EQ(betaRowsForTilt(B, M_PI), N);
  EXPECT_EQ(betaRowsForTilt(B, 0.0), 1);
  EXPECT_THROW(betaRowsForTilt(B, -1.0), InvalidArgument);
  EXPECT_THROW(corr->correlate(F, H, 1, -1), InvalidArgument);
}

namespace {

/** The target (first) and source spectra at bandwidth \a B: the target holds the
 *  source's lobes twice, rotated by a 5 deg tilt and, stronger, by a 70 deg tilt. */
std::pair<SphericalSpectrum, SphericalSpectrum> twiceTiltedLobes(int B)
{
  std::mt19937 rng(7);
  std::vector<Eigen::Vector3d> src, tgt;
  std::vector<double> w, wt;
  const Eigen::Matrix3d R_in = (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
                                Eigen::AngleAxisd(5.0 * kDeg, Eigen::Vector3d::UnitX()))
                                   .toRotationMatrix();
  const Eigen::Matrix3d R_out =
      (Eigen::AngleAxisd(2.0, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(70.0 * kDeg, Eigen::Vector3d::UnitY()))
          .toRotationMatrix();
  for (int i = 0; i < 8; ++i) {
    src.push_back(test::randomRotation(rng).col(0));
    w.push_back(1.0 + 0.3 * i);
    tgt.push_back(R_in * src.back());
    wt.push_back(w.back());
    tgt.push_back(R_out * src.back());
    wt.push_back(1.2 * w.back());
  }
  const auto sht = SphericalHarmonicTransform::instance(B);
  return {sht->forward(test::lobeSamples(B, tgt, wt, 0.6 * B).data()),
          sht->forward(test::lobeSamples(B, src, w, 0.6 * B).data())};
}

/** The maxima of \a full in the first \a rows - 1 beta rows that no stronger kept
 *  peak within 10 deg shadows, strongest first. */
std::vector<So3GridIndex> unshadowedInCone(const So3CorrelationGrid& full, int rows,
                                           int B)
{
  std::vector<So3GridIndex> in_cone;
  for (const So3GridIndex& p : distinctPeaks(full, 100000, 0.0, 2)) {
    bool shadowed = p.beta >= rows - 1;
    const Eigen::Matrix3d R = rotationFromEuler(gridEuler(p, B));
    for (const So3GridIndex& q : in_cone)
      shadowed = shadowed ||
                 rotationDistance(R, rotationFromEuler(gridEuler(q, B))) <= 10.0 * kDeg;
    if (!shadowed)
      in_cone.push_back(p);
  }
  return in_cone;
}

} // namespace

TEST(So3Correlation, LimitedRowsKeepInConePeaks)
{
  // The target holds the source's lobes twice: rotated by R_in (5 deg tilt) and,
  // stronger, by R_out (70 deg tilt). The global maximum lies outside a 20 deg cone;
  // the lesser peaks inside it are what a gravity prior keeps.
  const int B = 16;
  const auto [F, H] = twiceTiltedLobes(B);
  const auto corr = So3Correlator::instance(B);
  const So3CorrelationGrid full = corr->correlate(F, H, 2);
  const int rows = betaRowsForTilt(B, 20.0 * kDeg);
  const So3CorrelationGrid part = corr->correlate(F, H, 2, rows);
  const So3GridIndex global = full.argmax(2);
  EXPECT_GE(global.beta, rows) << "the fixture's best peak should be out of the cone";
  const std::vector<So3GridIndex> peaks = distinctPeaks(part, 5, 10.0 * kDeg, 2);
  ASSERT_FALSE(peaks.empty());
  const So3GridIndex best = part.argmax(2);
  EXPECT_EQ(peaks[0].beta, best.beta);
  EXPECT_EQ(peaks[0].alpha, best.alpha);
  EXPECT_EQ(peaks[0].gamma, best.gamma);
  double scale = 0.0;
  for (int j = 0; j < full.size(); ++j)
    for (int a = 0; a < full.size(); ++a)
      for (int c = 0; c < full.size(); ++c)
        scale = std::max(scale, std::abs(full(j, a, c)));
  for (const So3GridIndex& p : peaks) {
    // Inside the cone, with its neighbors computed, and a true maximum of the full
    // grid.
    EXPECT_LT(p.beta, rows - 1);
    const double tilt = gridEuler(p, B).beta;
    EXPECT_LE(tilt, 20.0 * kDeg);
    for (const RotationSample& s : rotationNeighborhood(full, p, 1))
      EXPECT_LE(s.value, full(p) + 1e-12 * scale);
  }
  // The full grid's in-cone maxima that no stronger peak shadows are kept, in order.
  const std::vector<So3GridIndex> in_cone = unshadowedInCone(full, rows, B);
  ASSERT_GE(in_cone.size(), 1u);
  for (std::size_t k = 0; k < std::min(in_cone.size(), peaks.size()); ++k) {
    EXPECT_EQ(in_cone[k].beta, peaks[k].beta) << k;
    EXPECT_EQ(in_cone[k].alpha, peaks[k].alpha) << k;
    EXPECT_EQ(in_cone[k].gamma, peaks[k].gamma) << k;
  }
}
