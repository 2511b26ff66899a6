/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Spec section 4.1 items 1-3: quadrature weights, Legendre functions, SHT.
 */
#include "so3_test_support.h"
#include "sphere/spherical_grid.h"
#include "sphere/spherical_harmonics.h"
#include "support/error.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace pcl::phaser;

TEST(SphericalGrid, WeightsIntegratePolynomialsExactly)
{
  for (int B : {1, 2, 5, 16, 64, 256}) {
    const std::vector<double> w = quadratureWeights(B);
    ASSERT_EQ(static_cast<int>(w.size()), 2 * B);
    for (int j = 0; j < 2 * B; ++j)
      EXPECT_NEAR(w[j], w[2 * B - 1 - j], 1e-15) << "B=" << B << " j=" << j;
    for (int k = 0; k <= 2 * B - 1; ++k) {
      double sum = 0.0;
      for (int j = 0; j < 2 * B; ++j)
        sum += w[j] * std::pow(std::cos(ringColatitude(j, B)), k);
      const double exact = (k % 2) ? 0.0 : 2.0 / (k + 1);
      EXPECT_NEAR(sum, exact, 1e-14) << "B=" << B << " k=" << k;
    }
  }
}

TEST(SphericalGrid, CellIndexMatchesSampleDirections)
{
  const int B = 8;
  for (int j = 0; j < 2 * B; ++j)
    for (int k = 0; k < 2 * B; ++k)
      EXPECT_EQ(cellIndex(3.5 * sampleDirection(j, k, B), B), j * 2 * B + k);
  EXPECT_EQ(cellIndex(Eigen::Vector3d::Zero(), B), -1);
  EXPECT_EQ(cellIndex(Eigen::Vector3d(NAN, 0, 1), B), -1);
  EXPECT_EQ(cellIndex(Eigen::Vector3d(0, 0, 1), B) / (2 * B), 0);          // north pole
  EXPECT_EQ(cellIndex(Eigen::Vector3d(0, 0, -1), B) / (2 * B), 2 * B - 1); // south pole
  EXPECT_EQ(cellIndex(Eigen::Vector3d(1, -1e-9, 0), B) % (2 * B), 0); // phi wraps to 0
}

/** The cell from the exact angles, as the grid defines it: ring floor(theta 2B / pi),
 *  column round(phi B / pi) mod 2B. */
int exactCell(const Eigen::Vector3d& p, int B)
{
  const int n = 2 * B;
  const double theta = std::atan2(std::hypot(p.x(), p.y()), p.z());
  double phi = std::atan2(p.y(), p.x());
  if (phi < 0.0)
    phi += 2.0 * M_PI;
  const int j = std::min(n - 1, static_cast<int>(theta * n / M_PI));
  return j * n + static_cast<int>(std::lround(phi * B / M_PI)) % n;
}

TEST(SphericalGrid, CellIndexIsTheExactCell)
{
  // cellIndex takes its angles from a polynomial away from the cell boundaries: random
  // directions at any scale, and directions within 1e-9 .. 1e-4 rad of a boundary.
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int B : {8, 32, 64, 128}) {
    const int n = 2 * B;
    for (int i = 0; i < 20000; ++i) {
      const Eigen::Vector3d d(gauss(rng), gauss(rng), gauss(rng));
      const double scale = std::pow(10.0, 6.0 * unit(rng));
      ASSERT_EQ(cellIndex(scale * d, B), exactCell(scale * d, B)) << d.transpose();
      const double offset =
          std::copysign(std::pow(10.0, -9.0 + 5.0 * std::abs(unit(rng))), unit(rng));
      const double theta = M_PI * (i % n) / n + offset;
      const double phi = M_PI * ((i / n) % n + 0.5) / B + offset;
      const Eigen::Vector3d b(std::sin(theta) * std::cos(phi),
                              std::sin(theta) * std::sin(phi), std::cos(theta));
      ASSERT_EQ(cellIndex(b, B), exactCell(b, B)) << b.transpose();
    }
  }
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(1e-300, -1e-300, 1e-300), Eigen::Vector3d(1e300, 1e300, -1e300),
        Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(-1, -0.0, 0),
        Eigen::Vector3d(0, 0, 5)})
    EXPECT_EQ(cellIndex(p, 64), exactCell(p, 64)) << p.transpose();
}

TEST(Legendre, ClosedForms)
{
  const int B = 4;
  for (double x : {-1.0, -0.7, -0.1, 0.0, 0.3, 0.95, 1.0}) {
    const double s = std::sqrt(1.0 - x * x);
    const std::vector<double> p = normalizedLegendre(B, x);
    EXPECT_NEAR(p[legendreIndex(0, 0, B)], 1.0 / std::sqrt(4 * M_PI), 1e-15);
    EXPECT_NEAR(p[legendreIndex(1, 0, B)], std::sqrt(3 / (4 * M_PI)) * x, 1e-15);
    EXPECT_NEAR(p[legendreIndex(1, 1, B)], -std::sqrt(3 / (8 * M_PI)) * s, 1e-15);
    EXPECT_NEAR(p[legendreIndex(2, 1, B)], -std::sqrt(15 / (8 * M_PI)) * s * x, 1e-15);
    EXPECT_NEAR(p[legendreIndex(2, 2, B)], 0.25 * std::sqrt(15 / (2 * M_PI)) * s * s,
                1e-15);
  }
}

TEST(Legendre, GramMatrixIsIdentityUpTo256)
{
  for (int B : {8, 64, 256}) {
    const std::vector<double> w = quadratureWeights(B);
    const int n = 2 * B;
    std::vector<std::vector<double>> rows(n);
    for (int j = 0; j < n; ++j)
      rows[j] = normalizedLegendre(B, std::cos(ringColatitude(j, B)));
    double worst = 0.0;
    for (int m = 0; m < B; ++m) {
      Eigen::MatrixXd P(n, B - m);
      for (int j = 0; j < n; ++j)
        for (int l = m; l < B; ++l)
          P(j, l - m) = rows[j][legendreIndex(l, m, B)];
      const Eigen::MatrixXd G =
          2 * M_PI * P.transpose() *
          Eigen::Map<const Eigen::VectorXd>(w.data(), n).asDiagonal() * P;
      worst = std::max(
          worst, (G - Eigen::MatrixXd::Identity(B - m, B - m)).cwiseAbs().maxCoeff());
    }
    EXPECT_LT(worst, 1e-13) << "B=" << B;
  }
}

TEST(SphericalHarmonicTransform, RoundTrip)
{
  std::mt19937 rng(7);
  for (int B : {1, 2, 3, 16, 64}) {
    const SphericalSpectrum F = test::randomSpectrum(B, rng);
    const auto sht = SphericalHarmonicTransform::instance(B);
    const std::vector<double> f = sht->inverse(F);
    const SphericalSpectrum G = sht->forward(f.data());
    EXPECT_LT((F - G).cwiseAbs().maxCoeff(), 1e-13) << "B=" << B;
    // Synthesis agrees with direct evaluation of sum F Y at the grid samples.
    if (B <= 16) {
      const int k = 1 % (2 * B);
      for (int j : {0, B, 2 * B - 1})
        EXPECT_NEAR(f[j * 2 * B + k], test::synthesize(F, sampleDirection(j, k, B)),
                    1e-12);
    }
  }
}

TEST(SphericalHarmonicTransform, AnalyticCoefficients)
{
  const int B = 16, n = 2 * B;
  std::vector<double> f(n * n), one(n * n, 1.0);
  for (int j = 0; j < n; ++j) {
    const std::vector<double> p = normalizedLegendre(B, std::cos(ringColatitude(j, B)));
    for (int k = 0; k < n; ++k)
      f[j * n + k] = p[legendreIndex(5, 3, B)] * std::cos(3 * columnAzimuth(k, B));
  }
  const auto sht = SphericalHarmonicTransform::instance(B);
  SphericalSpectrum F = sht->forward(f.data());
  EXPECT_NEAR(F(5, 3).real(), 0.5, 1e-12);
  EXPECT_NEAR(F(5, 3).imag(), 0.0, 1e-12);
  F(5, 3) = 0.0;
  EXPECT_LT(F.cwiseAbs().maxCoeff(), 1e-12);
  const SphericalSpectrum C = sht->forward(one.data());
  EXPECT_NEAR(C(0, 0).real(), std::sqrt(4 * M_PI), 1e-13);
  EXPECT_NEAR(spectrumSquaredNorm(C), 4 * M_PI, 1e-12);
}

TEST(SphericalHarmonicTransform, ThreadCountDoesNotChangeBits)
{
  // B = 32 runs on the calling thread whatever the count; B = 128 is split over them.
  for (const int B : {32, 128}) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<double> f(4 * B * B);
    for (double& v : f)
      v = u(rng);
    const auto sht = SphericalHarmonicTransform::instance(B);
    const SphericalSpectrum a = sht->forward(f.data(), 1);
    const SphericalSpectrum b = sht->forward(f.data(), 2);
    EXPECT_EQ(0,
              std::memcmp(a.data(), b.data(), sizeof(std::complex<double>) * a.size()))
        << "B = " << B;
  }
}

TEST(SphericalHarmonicTransform, RejectsIllegalBandwidth)
{
  EXPECT_THROW(SphericalHarmonicTransform::instance(0), InvalidArgument);
  EXPECT_THROW(SphericalHarmonicTransform::instance(257), InvalidArgument);
  EXPECT_THROW(SphericalHarmonicTransform(-3), InvalidArgument);
  EXPECT_THROW(quadratureWeights(1000), InvalidArgument);
  EXPECT_THROW(
      SphericalHarmonicTransform::instance(4)->inverse(SphericalSpectrum::Zero(3, 3)),
      InvalidArgument);
}
