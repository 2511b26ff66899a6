/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "so3/so3_correlation.h"
#include "so3_test_support.h"
#include "support/error.h"
#include "uncertainty/peak_neighborhood.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace pcl::phaser;

TEST(PeakNeighborhood, RotationBlockMatchesExactEvaluationAtThePoles)
{
  std::mt19937 rng(12);
  const int B = 8, N = 2 * B;
  const SphericalSpectrum F = test::randomSpectrum(B, rng);
  const SphericalSpectrum H = test::randomSpectrum(B, rng);
  const So3CorrelationGrid C = So3Correlator(B).correlate(F, H);
  double scale = 0.0;
  for (int j = 0; j < N; ++j)
    scale = std::max(scale, std::abs(C(j, 0, 0)));
  for (const So3GridIndex& peak :
       {So3GridIndex{0, 3, 5}, So3GridIndex{N - 1, 0, N - 1}, So3GridIndex{7, 9, 2}}) {
    const std::vector<RotationSample> block = rotationNeighborhood(C, peak, 2);
    ASSERT_EQ(block.size(), 125u);
    std::vector<Eigen::Matrix3d> rotations;
    for (const RotationSample& s : block)
      rotations.push_back(s.rotation);
    const std::vector<double> exact = evaluateCorrelation(F, H, rotations);
    for (std::size_t i = 0; i < block.size(); ++i)
      EXPECT_NEAR(block[i].value, exact[i], 1e-12 * scale) << "peak beta " << peak.beta;
  }
}

TEST(PeakNeighborhood, DistinctPeaksOfASymmetricScene)
{
  // Lobes invariant under a half turn about z: C has two equal maxima, R and R Rz(pi).
  const int B = 16;
  std::vector<Eigen::Vector3d> src;
  const Eigen::Matrix3d half_turn =
      Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).matrix();
  for (const Eigen::Vector3d& d :
       {Eigen::Vector3d(1, 0.2, 0.3), Eigen::Vector3d(0.1, 1, -0.5),
        Eigen::Vector3d(0.4, -0.3, 1)}) {
    src.push_back(d.normalized());
    src.push_back(half_turn * d.normalized());
  }
  const Eigen::Matrix3d R = rotationFromEuler({0.7, 1.1, -0.4});
  std::vector<Eigen::Vector3d> tgt;
  for (const auto& d : src)
    tgt.push_back(R * d);
  const std::vector<double> w(src.size(), 1.0);
  const auto sht = SphericalHarmonicTransform::instance(B);
  const SphericalSpectrum F =
      sht->forward(test::lobeSamples(B, tgt, w, 0.6 * B).data());
  const SphericalSpectrum H =
      sht->forward(test::lobeSamples(B, src, w, 0.6 * B).data());
  const So3CorrelationGrid C = So3Correlator::instance(B)->correlate(F, H);
  const std::vector<So3GridIndex> peaks = distinctPeaks(C, 3, 20.0 * M_PI / 180.0);
  ASSERT_GE(peaks.size(), 2u);
  const double tol = 1.5 * M_PI / (2 * B);
  const Eigen::Matrix3d first = rotationFromEuler(gridEuler(peaks[0], B));
  const Eigen::Matrix3d second = rotationFromEuler(gridEuler(peaks[1], B));
  const bool a =
      rotationDistance(first, R) < tol && rotationDistance(second, R * half_turn) < tol;
  const bool b =
      rotationDistance(second, R) < tol && rotationDistance(first, R * half_turn) < tol;
  EXPECT_TRUE(a || b);
  EXPECT_NEAR(C(peaks[0]), C(peaks[1]), 0.05 * C(peaks[0]));
  // The same peaks, in the same order, and the same argmax with any thread count.
  for (int threads : {2, 3, 7}) {
    const std::vector<So3GridIndex> again =
        distinctPeaks(C, 3, 20.0 * M_PI / 180.0, threads);
    ASSERT_EQ(again.size(), peaks.size());
    for (std::size_t k = 0; k < peaks.size(); ++k) {
      EXPECT_EQ(again[k].beta, peaks[k].beta);
      EXPECT_EQ(again[k].alpha, peaks[k].alpha);
      EXPECT_EQ(again[k].gamma, peaks[k].gamma);
    }
    const So3GridIndex m1 = C.argmax(), mt = C.argmax(threads);
    EXPECT_EQ(mt.beta, m1.beta);
    EXPECT_EQ(mt.alpha, m1.alpha);
    EXPECT_EQ(mt.gamma, m1.gamma);
    EXPECT_EQ(C(m1), C(peaks[0])); // the global maximum is the first distinct peak
  }
}
