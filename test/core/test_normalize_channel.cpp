/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The robust per-cloud channel normalization that precedes spectral fusion.
 */
#include "channels/spectral_fusion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using namespace pcl::phaser;

namespace {

double stddev(const Eigen::VectorXd& v)
{
  return std::sqrt((v.array() - v.mean()).square().mean());
}

} // namespace

TEST(NormalizeChannel, BringsDifferentScalesToComparableSpread)
{
  std::mt19937 rng(31);
  std::lognormal_distribution<double> range(2.5, 0.6);  // meters, ~5-40 m
  std::uniform_int_distribution<int> reflect(0, 65535); // raw uint16
  Eigen::VectorXd meters(5000), counts(5000);
  for (int i = 0; i < 5000; ++i) {
    meters[i] = range(rng);
    counts[i] = reflect(rng);
  }
  ASSERT_GT(stddev(counts) / stddev(meters), 1000.0);
  const Eigen::VectorXd a = normalizeChannel(meters), b = normalizeChannel(counts);
  for (const double spread : {stddev(a), stddev(b)}) {
    EXPECT_GT(spread, 0.6);
    EXPECT_LT(spread, 1.5);
  }
  EXPECT_LT(std::max(stddev(a), stddev(b)) / std::min(stddev(a), stddev(b)), 1.5);
  EXPECT_LE(a.cwiseAbs().maxCoeff(), 3.0);
}

TEST(NormalizeChannel, ExactValuesOutliersConstantsAndNonFinite)
{
  // median 3, |deviations| {2,1,0,1,97}: MAD 1, scale 1.4826; 100 is clamped.
  Eigen::VectorXd v(5);
  v << 1, 2, 3, 4, 100;
  const Eigen::VectorXd n = normalizeChannel(v);
  EXPECT_NEAR(n[0], -2.0 / 1.482602218505602, 1e-12);
  EXPECT_NEAR(n[2], 0.0, 1e-15);
  EXPECT_EQ(n[4], 3.0);
  EXPECT_EQ(normalizeChannel(v, 1.0)[0], -1.0);

  // Even count: the median is the mean of the middle pair.
  Eigen::VectorXd e(4);
  e << 10, 0, 30, 20;
  EXPECT_NEAR(normalizeChannel(e)[0] + normalizeChannel(e)[3], 0.0, 1e-15);

  EXPECT_TRUE(normalizeChannel(Eigen::VectorXd::Constant(7, 42.0)).isZero(0.0));
  EXPECT_EQ(normalizeChannel(Eigen::VectorXd()).size(), 0);

  // Mostly zeros (MAD = 0): falls back to the mean absolute deviation, stays finite.
  Eigen::VectorXd sparse = Eigen::VectorXd::Zero(10);
  sparse[3] = 500.0;
  sparse[8] = 1000.0;
  const Eigen::VectorXd s = normalizeChannel(sparse);
  EXPECT_TRUE(s.allFinite() && s[8] > s[3] && s[3] > 0.0 && s[0] == 0.0)
      << s.transpose();

  // Non-finite values map to 0 and do not change the statistics of the others.
  Eigen::VectorXd with(7);
  with << 1, 2, std::numeric_limits<double>::quiet_NaN(), 3, 4,
      std::numeric_limits<double>::infinity(), 100;
  const Eigen::VectorXd w = normalizeChannel(with);
  EXPECT_EQ(w[2], 0.0);
  EXPECT_EQ(w[5], 0.0);
  EXPECT_EQ(w[0], n[0]);
  EXPECT_EQ(w[6], n[4]);
}
