/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Spec section 4.1 items 4-5: Wigner d values, orthogonality, symmetries, rotation law.
 */
#include "so3/so3_correlation_grid.h"
#include "so3/wigner.h"
#include "so3_test_support.h"
#include "sphere/spherical_grid.h"
#include "support/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace pcl::phaser;

TEST(Wigner, CheckValues)
{
  for (double b : {0.0, 0.3, 1.2, M_PI / 2, 2.9, M_PI}) {
    const double s = std::sin(b), c = std::cos(b);
    EXPECT_NEAR(wignerSmallD(1, 0, 2, b)[1], -s / std::sqrt(2.0), 1e-15);
    EXPECT_NEAR(wignerSmallD(0, 1, 2, b)[1], s / std::sqrt(2.0), 1e-15);
    EXPECT_NEAR(wignerSmallD(1, 1, 2, b)[1], (1 + c) / 2, 1e-15);
    EXPECT_NEAR(wignerSmallD(1, -1, 2, b)[1], (1 - c) / 2, 1e-15);
    EXPECT_NEAR(wignerSmallD(2, 0, 3, b)[2], std::sqrt(3.0 / 8) * s * s, 1e-15);
    EXPECT_NEAR(wignerSmallD(0, 0, 2, b)[1], c, 1e-15);
    EXPECT_NEAR(wignerSmallD(0, 0, 2, b)[0], 1.0, 1e-15);
  }
}

TEST(Wigner, OrthogonalityUpTo256)
{
  const int B = 256;
  const std::vector<double> w = quadratureWeights(B);
  const int pairs[][2] = {{0, 0},   {3, -7},     {-40, 40},  {100, 13},
                          {255, 0}, {-255, 255}, {128, -200}};
  for (const auto& pr : pairs) {
    const int mp = pr[0], m = pr[1];
    std::vector<std::vector<double>> d(2 * B);
    for (int j = 0; j < 2 * B; ++j)
      d[j] = wignerSmallD(mp, m, B, ringColatitude(j, B));
    const int L = std::max(std::abs(mp), std::abs(m));
    double worst = 0.0;
    for (int l = L; l < B; l += 7)
      for (int l2 = L; l2 < B; l2 += 5) {
        double sum = 0.0;
        for (int j = 0; j < 2 * B; ++j)
          sum += w[j] * d[j][l] * d[j][l2];
        worst = std::max(worst, std::abs(sum - (l == l2 ? 2.0 / (2 * l + 1) : 0.0)));
      }
    EXPECT_LT(worst, 1e-12) << "m'=" << mp << " m=" << m;
  }
}

TEST(Wigner, StepTableEqualsTheDirectSteps)
{
  const int B = 40;
  const WignerStepTable table(B);
  double worst = 0.0;
  for (int m = -(B - 1); m < B; ++m)
    for (int mp = -(B - 1); mp < B; ++mp)
      for (int l = std::max(std::abs(m), std::abs(mp)); l + 1 < B; ++l) {
        const WignerStep direct = wignerStep(l, mp, m), tabled = table.step(l, mp, m);
        for (auto [x, y] :
             {std::pair{direct.a, tabled.a}, std::pair{direct.ac, tabled.ac},
              std::pair{direct.b, tabled.b}})
          worst = std::max(worst, std::abs(x - y) / std::max(1.0, std::abs(x)));
      }
  EXPECT_LT(worst, 1e-14);
  EXPECT_THROW(WignerStepTable(0), InvalidArgument);
}

TEST(Wigner, Symmetries)
{
  const int B = 12;
  for (double b : {0.2, 1.0, 2.5})
    for (int mp = -(B - 1); mp < B; mp += 3)
      for (int m = -(B - 1); m < B; m += 2) {
        const auto d = wignerSmallD(mp, m, B, b);
        const auto dt = wignerSmallD(m, mp, B, b);
        const auto dn = wignerSmallD(-m, -mp, B, b);
        const auto dnn = wignerSmallD(-mp, -m, B, b);
        const auto dpi = wignerSmallD(mp, m, B, M_PI - b);
        const auto dneg = wignerSmallD(-mp, m, B, b);
        for (int l = std::max(std::abs(mp), std::abs(m)); l < B; ++l) {
          const double sgn = ((mp - m) % 2) ? -1.0 : 1.0;
          EXPECT_NEAR(d[l], sgn * dt[l], 1e-13);
          EXPECT_NEAR(d[l], dn[l], 1e-13);
          EXPECT_NEAR(dnn[l], sgn * d[l], 1e-13);
          EXPECT_NEAR(dpi[l], (((l - m) % 2) ? -1.0 : 1.0) * dneg[l], 1e-13);
        }
      }
}

TEST(Wigner, RotationLaw)
{
  // Y_l^m(R^-1 w) = sum_m' Y_l^m'(w) D^l_{m'm}(R)
  std::mt19937 rng(11);
  const int B = 10;
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const EulerZYZ e = eulerFromRotation(R);
    const Eigen::Vector3d w = test::randomRotation(rng).col(0);
    const auto Y = test::sphericalHarmonics(B, w);
    const auto Yr = test::sphericalHarmonics(B, R.transpose() * w);
    for (int l = 0; l < B; ++l)
      for (int m = -l; m <= l; ++m) {
        std::complex<double> v = 0.0;
        for (int mp = -l; mp <= l; ++mp)
          v += Y[l][l + mp] * test::wignerD(l, mp, m, e);
        EXPECT_LT(std::abs(v - Yr[l][l + m]), 1e-13) << "l=" << l << " m=" << m;
      }
  }
}

TEST(So3Grid, EulerRoundTripAndPoles)
{
  std::mt19937 rng(5);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Matrix3d R = test::randomRotation(rng);
    const EulerZYZ e = eulerFromRotation(R);
    EXPECT_GE(e.beta, 0.0);
    EXPECT_LE(e.beta, M_PI);
    EXPECT_LT((rotationFromEuler(e) - R).norm(), 1e-12);
  }
  // Matrix form of spec section 4 for one triple.
  const EulerZYZ e{-1.0, 1.0, 0.3};
  const Eigen::Matrix3d R = rotationFromEuler(e);
  const double ca = std::cos(e.alpha), sa = std::sin(e.alpha), cb = std::cos(e.beta),
               sb = std::sin(e.beta), cg = std::cos(e.gamma), sg = std::sin(e.gamma);
  EXPECT_NEAR(R(0, 0), ca * cb * cg - sa * sg, 1e-15);
  EXPECT_NEAR(R(0, 2), ca * sb, 1e-15);
  EXPECT_NEAR(R(2, 0), -sb * cg, 1e-15);
  EXPECT_NEAR(R(2, 1), sb * sg, 1e-15);
  for (const EulerZYZ& pole : {EulerZYZ{0.4, 0.0, 0.3}, EulerZYZ{0.4, M_PI, 0.3}}) {
    const Eigen::Matrix3d P = rotationFromEuler(pole);
    EXPECT_LT((rotationFromEuler(eulerFromRotation(P)) - P).norm(), 1e-12);
  }
  EXPECT_NEAR(rotationDistance(Eigen::Matrix3d::Identity(),
                               rotationFromEuler({0.0, 1e-7, 0.0})),
              1e-7, 1e-15);
}
