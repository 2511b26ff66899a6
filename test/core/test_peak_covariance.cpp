/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The covariance model behind getCovariance(): sidelobe noise of a 3-D correlation,
 * error propagation through the sub-voxel peak (closed form and Monte Carlo), the
 * mismatch scaling, and the rotation block (Bingham spread + model error).
 */
#include "spatial/spatial_correlation.h"
#include "support/error.h"
#include "uncertainty/peak_neighborhood.h"

#include <pcl_phaser/core/bingham.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace pcl::phaser;

namespace {

constexpr int kN = 32;

/** A kN^3 volume holding an axis-aligned Gaussian peak of height \a height and widths
 *  \a width (voxels) at lag \a center, plus white noise of deviation \a sigma. */
SpatialVolume gaussianPeak(const Eigen::Vector3d& center, const Eigen::Vector3d& width,
                           double height, double sigma, std::mt19937& rng)
{
  SpatialVolume v;
  v.grid.dims = Eigen::Vector3i(kN, kN, kN);
  v.grid.voxel_size = 0.25;
  v.values.assign(v.grid.size(), 0.0);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int x = 0; x < kN; ++x)
    for (int y = 0; y < kN; ++y)
      for (int z = 0; z < kN; ++z) {
        const Eigen::Vector3d lag(x > kN / 2 ? x - kN : x, y > kN / 2 ? y - kN : y,
                                  z > kN / 2 ? z - kN : z);
        const Eigen::Vector3d d = (lag - center).cwiseQuotient(width);
        v.values[v.grid.flatIndex(x, y, z)] =
            height * std::exp(-0.5 * d.squaredNorm()) + sigma * noise(rng);
      }
  return v;
}

bool symmetricPositiveDefinite(const Eigen::Matrix3d& m)
{
  return (m - m.transpose()).norm() <= 1e-12 * m.norm() &&
         Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvalues().minCoeff() >
             0.0;
}

} // namespace

TEST(PeakCovariance, SidelobesOfWhiteNoise)
{
  // White noise of variance s^2: var(c[i+1] - c[i-1]) = 2 s^2, var(second diff.) = 6
  // s^2.
  std::mt19937 rng(3);
  const double sigma = 0.02;
  const SpatialVolume v = gaussianPeak({0, 0, 0}, {1.5, 1.5, 1.5}, 1.0, sigma, rng);
  const CorrelationSidelobes s = correlationSidelobes(v, Eigen::Vector3i::Zero());
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(s.first_difference_variance[a], 2 * sigma * sigma,
                0.1 * 2 * sigma * sigma);
    EXPECT_NEAR(s.second_difference_variance[a], 6 * sigma * sigma,
                0.1 * 6 * sigma * sigma);
  }
}

TEST(PeakCovariance, SubVoxelClosedFormOnACenteredGaussian)
{
  // A Gaussian of width w centered on a voxel, in the log domain: neighbors a = d =
  // A exp(-1 / (2 w^2)), curvature k = -1 / w^2, offset 0, so var = var_u / (a d) /
  // (4 k^2) = var_u w^4 exp(1 / w^2) / (4 A^2) voxel^2, whatever var_k is.
  std::mt19937 rng(1);
  const Eigen::Vector3d w(1.2, 2.0, 3.1);
  const double A = 5.0;
  const SpatialVolume v = gaussianPeak({0, 0, 0}, w, A, 0.0, rng);
  CorrelationSidelobes noise;
  noise.first_difference_variance = Eigen::Vector3d(1e-4, 2e-4, 4e-4);
  noise.second_difference_variance = Eigen::Vector3d(1.0, 1.0, 1.0);
  const Eigen::Matrix3d cov = subVoxelPeakCovariance(v, Eigen::Vector3i::Zero(), noise);
  const double voxel2 = v.grid.voxel_size * v.grid.voxel_size;
  for (int a = 0; a < 3; ++a) {
    const double expected = noise.first_difference_variance[a] * std::pow(w[a], 4) *
                            std::exp(1.0 / (w[a] * w[a])) / (4.0 * A * A) * voxel2;
    EXPECT_NEAR(cov(a, a), expected, 1e-9 * expected) << "axis " << a;
  }
  EXPECT_TRUE(cov.isDiagonal());
  EXPECT_TRUE(symmetricPositiveDefinite(cov));
  // Wider peaks (less curvature) are less precise.
  EXPECT_LT(cov(0, 0), cov(1, 1));
  EXPECT_LT(cov(1, 1), cov(2, 2));
}

TEST(PeakCovariance, SubVoxelCovarianceMatchesMonteCarlo)
{
  // The predicted covariance of findSpatialPeak's sub-voxel estimate, from the noise
  // the sidelobes measure, against the scatter of that estimate over noisy
  // realisations.
  std::mt19937 rng(7);
  const Eigen::Vector3d center(0.3, -0.2, 0.1), width(1.4, 1.8, 1.1);
  const double sigma = 0.01;
  const int trials = 300;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero(),
                  predicted = Eigen::Matrix3d::Zero();
  std::vector<Eigen::Vector3d> estimates;
  for (int i = 0; i < trials; ++i) {
    const SpatialVolume v = gaussianPeak(center, width, 1.0, sigma, rng);
    const SpatialCorrelationResult r =
        findSpatialPeak(v, SpatialPeakRefinement::kGaussian, 1, false);
    ASSERT_EQ(r.index, Eigen::Vector3i::Zero());
    estimates.push_back(r.shift);
    sum += r.shift;
    predicted += subVoxelPeakCovariance(v, r.index, correlationSidelobes(v, r.index));
  }
  const Eigen::Vector3d mean = sum / trials;
  for (const Eigen::Vector3d& e : estimates)
    scatter += (e - mean) * (e - mean).transpose();
  scatter /= trials - 1;
  predicted /= trials;
  EXPECT_LT((mean - center * 0.25).norm(), 0.02 * 0.25); // the estimate is unbiased
  for (int a = 0; a < 3; ++a) // 300 samples: the variance is known to about +-8 %
    EXPECT_NEAR(predicted(a, a), scatter(a, a), 0.25 * scatter(a, a)) << "axis " << a;
  // Axes are independent in the model; the empirical cross terms are small.
  EXPECT_LT(std::abs(scatter(0, 1)), 0.25 * std::sqrt(scatter(0, 0) * scatter(1, 1)));
}

TEST(PeakCovariance, TranslationCovarianceScalesWithTheMismatch)
{
  std::mt19937 rng(11);
  const SpatialVolume v =
      gaussianPeak({0.2, 0.1, -0.3}, {1.5, 2.0, 1.2}, 1.0, 0.01, rng);
  const Eigen::Vector3i peak = Eigen::Vector3i::Zero();
  const double c = v.values[v.grid.flatIndex(0, 0, 0)];
  const Eigen::Matrix3d full =
      subVoxelPeakCovariance(v, peak, correlationSidelobes(v, peak));
  const Eigen::Matrix3d model = interpolationModelCovariance(v, peak);
  for (double rho2 : {0.5, 0.9, 0.99}) { // rho^2 = c^2 / (|f|^2 |g|^2)
    const Eigen::Matrix3d cov = translationCovariance(v, peak, c * c / rho2);
    EXPECT_TRUE(symmetricPositiveDefinite(cov));
    EXPECT_LT((cov - (1.0 - rho2) * full - model).norm(), 1e-9 * full.norm()) << rho2;
  }
  // Identical clouds (rho = 1) still give a definite matrix.
  EXPECT_TRUE(symmetricPositiveDefinite(translationCovariance(v, peak, c * c)));
  EXPECT_THROW(translationCovariance(v, peak, 0.0), InvalidArgument);
  EXPECT_THROW(translationCovariance(v, peak, std::nan("")), InvalidArgument);
}

TEST(PeakCovariance, SpectrumEnergyIsParseval)
{
  std::mt19937 rng(5);
  SpatialVolume v = gaussianPeak({1, 2, 3}, {2, 2, 2}, 1.0, 0.3, rng);
  v.grid.dims = Eigen::Vector3i(kN, kN, kN);
  double direct = 0.0;
  for (double x : v.values)
    direct += x * x;
  EXPECT_NEAR(spectrumEnergy(computeSpectrum(v)), direct, 1e-9 * direct);
  // Odd nz: no Nyquist plane.
  SpatialVolume odd;
  odd.grid.dims = Eigen::Vector3i(6, 5, 7);
  odd.grid.voxel_size = 1.0;
  std::normal_distribution<double> n(0.0, 1.0);
  direct = 0.0;
  for (std::size_t i = 0; i < odd.grid.size(); ++i) {
    odd.values.push_back(n(rng));
    direct += odd.values.back() * odd.values.back();
  }
  EXPECT_NEAR(spectrumEnergy(computeSpectrum(odd)), direct, 1e-9 * direct);
}

TEST(PeakCovariance, RotationCovarianceAddsTheModelErrorAndShrinksWithBandwidth)
{
  // A concentrated Bingham: tangent covariance ~ diag(-2 / Z), thin about one axis.
  const Eigen::Matrix4d M = Eigen::Matrix4d::Identity().rowwise().reverse();
  const BinghamDistribution b = makeBingham(M, Eigen::Vector4d(-1e6, -2e4, -5e3, 0.0));
  const Eigen::Matrix3d spread = b.tangentCovariance();
  double previous = std::numeric_limits<double>::infinity();
  for (int B : {16, 32, 64, 128}) {
    const Eigen::Matrix3d cov = rotationCovariance(b, B);
    const double s = kRotationModelErrorScale * M_PI / B;
    EXPECT_DOUBLE_EQ(rotationModelError(B), s);
    EXPECT_LT((cov - spread - s * s * Eigen::Matrix3d::Identity()).norm(),
              1e-12 * cov.norm());
    EXPECT_TRUE(symmetricPositiveDefinite(cov));
    // Even the thin direction is at least the model error.
    EXPECT_GE(
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvalues().minCoeff(),
        s * s * (1 - 1e-12));
    EXPECT_LT(cov.trace(), previous);
    previous = cov.trace();
  }
  EXPECT_THROW(rotationModelError(0), InvalidArgument);
}

TEST(PeakCovariance, InterpolationModelErrorIsTheDisagreementOfTwoVertices)
{
  std::mt19937 rng(2);
  // A symmetric peak: both vertices are 0, no model error.
  const SpatialVolume centered =
      gaussianPeak({0, 0, 0}, {1.0, 1.0, 1.0}, 1.0, 0.0, rng);
  EXPECT_LT(interpolationModelCovariance(centered, Eigen::Vector3i::Zero()).norm(),
            1e-20);
  // A sharp Gaussian off the voxel center: the log vertex is exact, the parabola is
  // not.
  const Eigen::Vector3d center(0.3, -0.2, 0.1);
  const SpatialVolume sharp = gaussianPeak(center, {0.7, 0.7, 0.7}, 1.0, 0.0, rng);
  const Eigen::Matrix3d cov =
      interpolationModelCovariance(sharp, Eigen::Vector3i::Zero());
  EXPECT_TRUE(cov.isDiagonal());
  for (int a = 0; a < 3; ++a) {
    Eigen::Vector3i m = Eigen::Vector3i::Zero(), p = m;
    m[a] = kN - 1;
    p[a] = 1;
    const double va = sharp.values[sharp.grid.flatIndex(m.x(), m.y(), m.z())];
    const double vb = sharp.values[0];
    const double vd = sharp.values[sharp.grid.flatIndex(p.x(), p.y(), p.z())];
    const double parabola = 0.5 * (va - vd) / (va - 2 * vb + vd);
    const double diff = (center[a] - parabola) * sharp.grid.voxel_size;
    EXPECT_NEAR(cov(a, a), diff * diff, 1e-9 * diff * diff + 1e-15) << "axis " << a;
    EXPECT_GT(cov(a, a), 0.0);
  }
  // It is part of translationCovariance.
  const double c = sharp.values[0];
  const Eigen::Matrix3d noise_free =
      translationCovariance(sharp, Eigen::Vector3i::Zero(), 2 * c * c);
  EXPECT_GE((noise_free - cov).diagonal().minCoeff(), -1e-15);
}
