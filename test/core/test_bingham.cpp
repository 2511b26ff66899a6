/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Bingham distribution: normalization constant against independent quadratures, MLE,
 * fit, sampler and rotation-vector covariance.
 */
#include "support/error.h"

#include <pcl_phaser/core/bingham.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/QR>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/special_functions/bessel.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace pcl::phaser;

namespace {

/** \a n independent samples of \a d (unit quaternions, w >= 0) by rejection from an
 *  angular central Gaussian envelope (Kent, Ganeiber & Mardia 2013). */
std::vector<Eigen::Vector4d> sample(const BinghamDistribution& d, std::size_t n,
                                    std::mt19937& rng)
{
  // exp(-x^T A x), A = diag(lambda) >= 0 in the frame of M, is bounded by B (x^T W
  // x)^{-2}, W = I + 2A/b, B = exp(-(4 - b)/2) (4/b)^2; b solves sum_i 1/(b + 2
  // lambda_i) = 1.
  const Eigen::Vector4d lambda = (d.Z.maxCoeff() - d.Z.array()).matrix();
  double lo = 0.0, hi = 4.0; // the root lies in (0, 4] since min lambda = 0
  for (int i = 0; i < 200; ++i) {
    const double b = 0.5 * (lo + hi);
    ((1.0 / (b + 2.0 * lambda.array())).sum() > 1.0 ? lo : hi) = b;
  }
  const double b = hi, log_bound = -(4.0 - b) / 2.0 + 2.0 * std::log(4.0 / b);
  const Eigen::Vector4d stddev =
      (1.0 / (1.0 + 2.0 * lambda.array() / b)).sqrt().matrix();
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform;
  std::vector<Eigen::Vector4d> out;
  out.reserve(n);
  while (out.size() < n) {
    Eigen::Vector4d x;
    for (int i = 0; i < 4; ++i)
      x(i) = stddev(i) * normal(rng);
    if (x.norm() == 0.0)
      continue;
    x.normalize();
    const double y = lambda.dot(x.cwiseAbs2());
    if (std::log(uniform(rng)) < -y + 2.0 * std::log1p(2.0 * y / b) - log_bound) {
      Eigen::Vector4d q = d.M * x;
      out.push_back(q(0) < 0.0 ? Eigen::Vector4d(-q) : q);
    }
  }
  return out;
}

const double kPi = 3.14159265358979323846;

struct Reference {
  double f = 0.0;
  Eigen::Vector4d df = Eigen::Vector4d::Zero();
  Eigen::Matrix4d d2f = Eigen::Matrix4d::Zero();
};

/** F, dF, d2F without Bessel functions: Hopf coordinates (sqrt(t) cos a, sqrt(t) sin a,
 *  sqrt(1-t) cos b, sqrt(1-t) sin b), dx = dt da db / 2, the periodic a and b
 *  integrals by the trapezoidal rule (exponentially convergent), t by 20-point
 *  Gauss-Legendre on a mesh graded with ratio 2 towards both ends. Pairs (z0, z1) and
 *  (z2, z3) in the given order, unlike the library, which pairs by sorted value. */
Reference hopfReference(const Eigen::Vector4d& z)
{
  const double u = 0.5 * std::max(std::abs(z(0) - z(1)), std::abs(z(2) - z(3)));
  const int n = 64 + int(17.0 * std::sqrt(u));
  std::vector<double> cos2(n), sin2(n);
  for (int k = 0; k < n; ++k) {
    cos2[k] = std::pow(std::cos(2 * kPi * k / n), 2);
    sin2[k] = 1.0 - cos2[k];
  }
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  // moments {1, c^2, s^2, c^4, s^4, c^2 s^2} of one circle
  const auto circle = [&](double a, double b) {
    Vec6 m = Vec6::Zero();
    for (int k = 0; k < n; ++k) {
      const double c = cos2[k], s = sin2[k], e = std::exp(a * c + b * s);
      m += e * (Vec6() << 1, c, s, c * c, s * s, c * s).finished();
    }
    return Vec6(m * (2 * kPi / n));
  };
  std::vector<double> mesh{0.0, 0.5, 1.0};
  for (double h = 0.25; h > 1e-10; h *= 0.5) {
    mesh.push_back(h);
    mesh.push_back(1.0 - h);
  }
  std::sort(mesh.begin(), mesh.end());
  using Gauss = boost::math::quadrature::gauss<double, 20>;
  Reference r;
  for (std::size_t i = 0; i + 1 < mesh.size(); ++i) {
    const double c = 0.5 * (mesh[i] + mesh[i + 1]), h = 0.5 * (mesh[i + 1] - mesh[i]);
    for (std::size_t j = 0; j < Gauss::abscissa().size(); ++j)
      for (double sign : {-1.0, 1.0}) {
        const double t = c + sign * h * Gauss::abscissa()[j], s = 1.0 - t;
        const double w = 0.5 * h * Gauss::weights()[j];
        const Vec6 p = circle(t * z(0), t * z(1)), q = circle(s * z(2), s * z(3));
        r.f += w * p(0) * q(0);
        r.df += w * Eigen::Vector4d(t * p(1) * q(0), t * p(2) * q(0), s * p(0) * q(1),
                                    s * p(0) * q(2));
        Eigen::Matrix4d m;
        m << t * t * p(3) * q(0), t * t * p(5) * q(0), t * s * p(1) * q(1),
            t * s * p(1) * q(2), 0, t * t * p(4) * q(0), t * s * p(2) * q(1),
            t * s * p(2) * q(2), 0, 0, s * s * p(0) * q(3), s * s * p(0) * q(5), 0, 0,
            0, s * s * p(0) * q(4);
        r.d2f += w * Eigen::Matrix4d(m.selfadjointView<Eigen::Upper>());
      }
  }
  return r;
}

/** F and dF by brute force in hyperspherical coordinates (x4 = cos psi, x3 = sin psi
 *  cos th, ...), Gauss-Legendre in psi and th, trapezoid in phi; mild Z only. */
Reference hypersphericalReference(const Eigen::Vector4d& z)
{
  using Gauss = boost::math::quadrature::gauss<double, 60>;
  std::vector<double> nodes, weights;
  for (std::size_t j = 0; j < Gauss::abscissa().size(); ++j)
    for (double sign : {-1.0, 1.0}) {
      nodes.push_back(0.5 * kPi * (1.0 + sign * Gauss::abscissa()[j]));
      weights.push_back(0.5 * kPi * Gauss::weights()[j]);
    }
  const int n_phi = 80;
  Reference r;
  for (std::size_t a = 0; a < nodes.size(); ++a)
    for (std::size_t b = 0; b < nodes.size(); ++b)
      for (int c = 0; c < n_phi; ++c) {
        const double psi = nodes[a], th = nodes[b], phi = 2 * kPi * c / n_phi;
        const Eigen::Vector4d x(std::sin(psi) * std::sin(th) * std::cos(phi),
                                std::sin(psi) * std::sin(th) * std::sin(phi),
                                std::sin(psi) * std::cos(th), std::cos(psi));
        const double w = weights[a] * weights[b] * (2 * kPi / n_phi) *
                         std::pow(std::sin(psi), 2) * std::sin(th);
        const double e = w * std::exp(z.dot(x.cwiseAbs2()));
        r.f += e;
        r.df += e * x.cwiseAbs2();
      }
  return r;
}

Eigen::Matrix4d randomOrthonormal(std::mt19937& rng)
{
  std::normal_distribution<double> normal;
  Eigen::Matrix4d a;
  for (int i = 0; i < 16; ++i)
    a(i) = normal(rng);
  return Eigen::HouseholderQR<Eigen::Matrix4d>(a).householderQ();
}

Eigen::Quaterniond toQuat(const Eigen::Vector4d& q)
{
  return Eigen::Quaterniond(q(0), q(1), q(2), q(3));
}

/** Rotation vector of a unit quaternion (taken with w >= 0). */
Eigen::Vector3d logMap(Eigen::Quaterniond q)
{
  if (q.w() < 0)
    q.coeffs() *= -1.0;
  const double r = q.vec().norm();
  return r == 0.0 ? Eigen::Vector3d::Zero()
                  : Eigen::Vector3d(2.0 * std::atan2(r, q.w()) / r * q.vec());
}

double relErr(double a, double b)
{
  return std::abs(a - b) / std::abs(b);
}

} // namespace

TEST(Bingham, ScaledBesselMatchesBoost)
{
  for (int n = 0; n <= 2; ++n)
    for (double x : {0.0, 1e-8, 0.3, 2.0, 7.5, 10.5, 12.5, 15.0, 17.5, 19.99, 20.0,
                     20.01, 25.0, 35.0, 120.0, 650.0}) {
      const double expected = boost::math::cyl_bessel_i(n, x) * std::exp(-x);
      EXPECT_NEAR(detail::scaledBesselI(n, x), expected, 2e-15 + 1e-14 * expected)
          << "n " << n << " x " << x;
    }
  // Far beyond double range of I_n: e^{-x} I_n(x) sqrt(2 pi x) = 1 - (4n^2-1)/(8x) + ..
  for (int n = 0; n <= 2; ++n) {
    const double x = 1e7;
    EXPECT_NEAR(detail::scaledBesselI(n, x) * std::sqrt(2 * kPi * x),
                1.0 - (4.0 * n * n - 1.0) / (8 * x), 1e-13);
  }
  EXPECT_THROW(detail::scaledBesselI(3, 1.0), InvalidArgument);
}

TEST(Bingham, ClosedForms)
{
  const BinghamNormalizer n0 = binghamNormalizer(Eigen::Vector4d::Zero());
  EXPECT_NEAR(n0.f, 2 * kPi * kPi, 1e-14 * n0.f); // area of S^3
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(n0.df(i), kPi * kPi / 2, 1e-14);
  for (double c : {-3.0, -250.0, 2.5}) {
    const BinghamNormalizer n = binghamNormalizer(Eigen::Vector4d::Constant(c));
    EXPECT_NEAR(relErr(n.f, 2 * kPi * kPi * std::exp(c)), 0.0, 1e-13) << c;
    EXPECT_NEAR(n.log_f, std::log(2 * kPi * kPi) + c, 1e-13);
    for (int i = 0; i < 4; ++i)
      EXPECT_NEAR(n.moments(i), 0.25, 1e-14);
  }
  // Two antipodal Gaussian peaks with the first metric correction:
  // F = 2 pi^{3/2} / sqrt(prod lambda) (1 + sum 1/(4 lambda) + O(lambda^-2)).
  const Eigen::Vector4d z(-1e6, -5e5, -1e5, 0.0);
  const double lambda = -z(0) * z(1) * z(2);
  const double asymptotic = 2 * std::pow(kPi, 1.5) / std::sqrt(lambda) *
                            (1 - 0.25 * (1 / z(0) + 1 / z(1) + 1 / z(2)));
  EXPECT_NEAR(relErr(binghamNormalizer(z).f, asymptotic), 0.0, 1e-9);
}

TEST(Bingham, MatchesIndependentQuadrature)
{
  const std::vector<Eigen::Vector4d> cases = {
      {-1, -2, -3, 0},          {0, -1, -2, -3},
      {-10, -10, -50, 0},       {-0.5, 0, -7, -2},
      {-100, -20, -5, 0},       {-300, -800, -2000, 0},
      {-5000, -5000, -5000, 0}, {-5000, -1, -2500, 0},
      {-4000, -3000, 0, -4500}, {3, -2, 1, 0},
      {-5000, -4990, -20, -3}};
  for (const Eigen::Vector4d& z : cases) {
    const BinghamNormalizer n = binghamNormalizer(z, true);
    const Reference r = hopfReference(z);
    EXPECT_LT(relErr(n.f, r.f), 1e-10) << z.transpose();
    for (int i = 0; i < 4; ++i) {
      EXPECT_LT(relErr(n.df(i), r.df(i)), 1e-10) << z.transpose() << " i " << i;
      for (int j = 0; j < 4; ++j)
        EXPECT_LT(relErr(n.fourth_moments(i, j), r.d2f(i, j) / r.f), 1e-9)
            << z.transpose() << " " << i << j;
    }
    // sum_i x_i^2 = 1 on the sphere
    EXPECT_LT(relErr(n.df.sum(), n.f), 1e-13);
    EXPECT_LT((n.fourth_moments.rowwise().sum() - n.moments).norm(), 1e-13);
    // log F and F agree, and fourth moments are not computed unless requested
    EXPECT_LT(relErr(std::exp(n.log_f), n.f), 1e-14);
    EXPECT_EQ(binghamNormalizer(z).fourth_moments, Eigen::Matrix4d::Zero());
  }
}

TEST(Bingham, MatchesHypersphericalQuadrature)
{
  for (const Eigen::Vector4d& z :
       {Eigen::Vector4d(-1, -2, -3, 0), Eigen::Vector4d(-4, 0, -0.5, -6),
        Eigen::Vector4d(1, -3, 0.5, -1)}) {
    const BinghamNormalizer n = binghamNormalizer(z);
    const Reference r = hypersphericalReference(z);
    EXPECT_LT(relErr(n.f, r.f), 1e-11) << z.transpose();
    for (int i = 0; i < 4; ++i)
      EXPECT_LT(relErr(n.df(i), r.df(i)), 1e-11) << z.transpose();
  }
}

TEST(Bingham, MaximumLikelihoodInvertsMoments)
{
  for (const Eigen::Vector4d& z :
       {Eigen::Vector4d(-1, -2, -3, 0), Eigen::Vector4d(-5, -5, -20, 0),
        Eigen::Vector4d(0, -0.01, 0, -3), Eigen::Vector4d(-200, 0, -100, -50),
        Eigen::Vector4d(-300, -800, -2000, 0), Eigen::Vector4d(-9e5, -1e4, -0.5, 0)}) {
    double residual = 1.0;
    const Eigen::Vector4d fitted =
        binghamMaximumLikelihood(binghamNormalizer(z).moments, &residual);
    EXPECT_LT(residual, 1e-9);
    for (int i = 0; i < 4; ++i)
      EXPECT_NEAR(fitted(i), z(i), 1e-7 * (1.0 + std::abs(z(i)))) << z.transpose();
  }
  // uniform scatter: Z = 0; unnormalized input is accepted
  EXPECT_LT(binghamMaximumLikelihood(Eigen::Vector4d::Constant(3.0)).norm(), 1e-12);
  // omega_i -> 0 is capped: the MLE is unbounded there
  const Eigen::Vector4d capped =
      binghamMaximumLikelihood(Eigen::Vector4d(0, 0.3, 0, 0.7));
  for (int i : {0, 2}) {
    EXPECT_GE(capped(i), -kMaxBinghamConcentration);
    EXPECT_LE(capped(i), -0.99 * kMaxBinghamConcentration);
  }
  EXPECT_LT(capped(1), 0.0);
  EXPECT_GT(capped(1), -10.0);
  EXPECT_EQ(capped(3), 0.0);
  EXPECT_THROW(binghamMaximumLikelihood(Eigen::Vector4d(-0.1, 0.3, 0.3, 0.5)),
               InvalidArgument);
  EXPECT_THROW(binghamMaximumLikelihood(Eigen::Vector4d::Zero()), InvalidArgument);
}

TEST(Bingham, SamplerMatchesExactMoments)
{
  std::mt19937 rng(7);
  for (const Eigen::Vector4d& z :
       {Eigen::Vector4d(-10, -5, -2, 0), Eigen::Vector4d(-200, -100, -50, 0)}) {
    const BinghamDistribution d = makeBingham(randomOrthonormal(rng), z);
    const std::vector<Eigen::Vector4d> s = sample(d, 20000, rng);
    Eigen::Vector4d mean_x2 = Eigen::Vector4d::Zero();
    for (const Eigen::Vector4d& q : s) {
      EXPECT_NEAR(q.norm(), 1.0, 1e-12);
      mean_x2 += (d.M.transpose() * q).cwiseAbs2() / double(s.size());
    }
    const Eigen::Vector4d exact = d.dF / d.F;
    for (int i = 0; i < 3; ++i) // relative standard error of a mean of x^2: <= 1%
      EXPECT_LT(relErr(mean_x2(i), exact(i)), 0.04) << z.transpose() << " " << i;
  }
  // deterministic given the seed
  const BinghamDistribution d =
      makeBingham(Eigen::Matrix4d::Identity(), {-3, -2, -1, 0});
  std::mt19937 a(3), b(3);
  EXPECT_EQ(sample(d, 50, a), sample(d, 50, b));
}

TEST(Bingham, FitRecoversDistributionFromSamples)
{
  std::mt19937 rng(11);
  const BinghamDistribution truth =
      makeBingham(randomOrthonormal(rng), Eigen::Vector4d(-200, -100, -50, 0));
  std::vector<Eigen::Vector4d> s = sample(truth, 20000, rng);
  for (std::size_t i = 0; i < s.size(); i += 2)
    s[i] = -s[i]; // antipodal symmetry: the sign of a sample is irrelevant
  const BinghamDistribution fit = fitBingham(s);
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(relErr(fit.Z(i), truth.Z(i)), 0.05) << i;
    EXPECT_GT(std::abs(fit.M.col(i).dot(truth.M.col(i))), 0.99) << i;
  }
  EXPECT_EQ(fit.Z(3), 0.0);
  const double angle = toQuat(fit.mode()).angularDistance(toQuat(truth.mode()));
  EXPECT_LT(angle, 0.5 * kPi / 180);
  EXPECT_GE(fit.mode()(0), 0.0);
  EXPECT_NEAR(fit.moment().trace(), 1.0, 1e-12);
  // F and dF belong to the fitted Z
  EXPECT_LT(relErr(fit.F, binghamNormalizer(fit.Z).f), 1e-14);
}

TEST(Bingham, WeightsEqualDuplication)
{
  std::mt19937 rng(5);
  const BinghamDistribution d =
      makeBingham(randomOrthonormal(rng), Eigen::Vector4d(-30, -20, -8, 0));
  const std::vector<Eigen::Vector4d> s = sample(d, 40, rng);
  std::vector<Eigen::Vector4d> duplicated;
  std::vector<double> weights;
  for (std::size_t i = 0; i < s.size(); ++i) {
    weights.push_back(double(i % 3)); // includes zero weights
    for (std::size_t k = 0; k < i % 3; ++k)
      duplicated.push_back(s[i]);
  }
  const BinghamDistribution a = fitBingham(s, weights), b = fitBingham(duplicated);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(a.Z(i), b.Z(i), 1e-8 * (1 + std::abs(b.Z(i))));
    EXPECT_NEAR(std::abs(a.M.col(i).dot(b.M.col(i))), 1.0, 1e-10);
  }
  // scaling all weights, or the quaternions' norms, changes nothing
  std::vector<double> scaled = weights;
  std::vector<Eigen::Vector4d> longer = s;
  for (std::size_t i = 0; i < s.size(); ++i) {
    scaled[i] *= 7.5;
    longer[i] *= 1.0 + double(i);
  }
  EXPECT_LT((fitBingham(longer, scaled).Z - a.Z).norm(), 1e-8 * a.Z.norm());
}

TEST(Bingham, SingleSampleIsModeWithCappedConcentration)
{
  const Eigen::Vector4d q = Eigen::Vector4d(0.3, -0.5, 0.1, 0.8).normalized();
  for (double sign : {1.0, -1.0}) {
    const BinghamDistribution d = fitBingham({sign * q}, {0.25});
    EXPECT_LT((d.mode() - q).norm(), 1e-12);
    for (int i = 0; i < 3; ++i) {
      EXPECT_GE(d.Z(i), -kMaxBinghamConcentration);
      EXPECT_LE(d.Z(i), -0.99 * kMaxBinghamConcentration);
    }
    EXPECT_TRUE(std::isfinite(d.F) && d.F > 0.0);
    EXPECT_NEAR(d.tangentCovariance().trace(), 6.0 / kMaxBinghamConcentration, 1e-8);
  }
}

TEST(Bingham, TangentCovarianceMatchesSamples)
{
  std::mt19937 rng(23);
  // concentrated (close to the first-order -2/z) and spread (far from it)
  for (const Eigen::Vector4d& z :
       {Eigen::Vector4d(-200, -100, -50, 0), Eigen::Vector4d(-10, -5, -2, 0)}) {
    const BinghamDistribution d = makeBingham(randomOrthonormal(rng), z);
    const std::vector<Eigen::Vector4d> s = sample(d, 30000, rng);
    const Eigen::Quaterniond mode = toQuat(d.mode());
    for (TangentFrame frame : {TangentFrame::kGlobal, TangentFrame::kLocal}) {
      Eigen::Matrix3d empirical = Eigen::Matrix3d::Zero();
      for (const Eigen::Vector4d& q : s) {
        const Eigen::Quaterniond err = frame == TangentFrame::kGlobal
                                           ? toQuat(q) * mode.conjugate()
                                           : mode.conjugate() * toQuat(q);
        const Eigen::Vector3d e = logMap(err);
        empirical += e * e.transpose() / double(s.size());
      }
      const Eigen::Matrix3d cov = d.tangentCovariance(frame);
      // compare in the principal axes, relative to the standard deviations
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
      const Eigen::Matrix3d v = eig.eigenvectors();
      const Eigen::Matrix3d rel = v.transpose() * empirical * v;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const double norm = std::sqrt(eig.eigenvalues()(i) * eig.eigenvalues()(j));
          EXPECT_NEAR(rel(i, j) / norm, i == j ? 1.0 : 0.0, 0.05)
              << z.transpose() << " " << i << j;
        }
    }
    // the frames are related by the mode's rotation
    const Eigen::Matrix3d r = mode.toRotationMatrix();
    EXPECT_LT((d.tangentCovariance(TangentFrame::kLocal) -
               r.transpose() * d.tangentCovariance() * r)
                  .norm(),
              1e-10);
  }
  // concentrated limit: V diag(-2/z) V^T with relative O(1/|z|) corrections
  const BinghamDistribution c =
      makeBingham(Eigen::Matrix4d::Identity(), {-4e4, -2e4, -1e4, 0});
  const Eigen::Vector3d diag = c.tangentCovariance().diagonal();
  EXPECT_NEAR(diag(2) / (2.0 / 4e4), 1.0, 1e-3); // m_0 * conj(mode) is the z axis
  EXPECT_NEAR(diag(1) / (2.0 / 2e4), 1.0, 1e-3);
  EXPECT_NEAR(diag(0) / (2.0 / 1e4), 1.0, 1e-3);
  // uniform: E[theta^2] = pi^2/3 + 2 for rotation angles of uniform rotations
  const Eigen::Matrix3d u = BinghamDistribution().tangentCovariance();
  EXPECT_LT((u - (kPi * kPi / 9 + 2.0 / 3) * Eigen::Matrix3d::Identity()).norm(),
            1e-10);
}

TEST(Bingham, DistributionBasics)
{
  // makeBingham sorts by concentration and shifts the maximum to zero
  const Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  const BinghamDistribution d = makeBingham(m, Eigen::Vector4d(5, 1, 3, 2));
  EXPECT_EQ(d.Z, Eigen::Vector4d(-4, -3, -2, 0));
  EXPECT_EQ(d.M.col(0), m.col(1));
  EXPECT_EQ(d.M.col(3), m.col(0));
  // pdf: antipodally symmetric, scale-invariant, normalized (F = int exp(..) over S^3)
  const Eigen::Vector4d q = Eigen::Vector4d(0.1, 0.7, -0.2, 0.4).normalized();
  EXPECT_DOUBLE_EQ(d.pdf(q), d.pdf(-q));
  EXPECT_DOUBLE_EQ(d.pdf(q), d.pdf(3.0 * q));
  const Reference r = hypersphericalReference(d.Z);
  EXPECT_LT(relErr(d.F, r.f), 1e-11);
  EXPECT_NEAR(d.pdf(d.mode()), 1.0 / d.F, 1e-15);
  // moment: exact E[q q^T]
  EXPECT_LT((d.moment() - d.M * (r.df / r.f).asDiagonal() * d.M.transpose()).norm(),
            1e-11);
  // the default is uniform
  const BinghamDistribution uniform;
  EXPECT_NEAR(uniform.pdf(q), 1.0 / (2 * kPi * kPi), 1e-16);
  EXPECT_LT((uniform.moment() - 0.25 * Eigen::Matrix4d::Identity()).norm(), 1e-15);
}

TEST(Bingham, RejectsBadInput)
{
  const Eigen::Vector4d q(1, 0, 0, 0);
  EXPECT_THROW(fitBingham({}), InvalidArgument);
  EXPECT_THROW(fitBingham({q, q}, {1.0}), InvalidArgument);
  EXPECT_THROW(fitBingham({q, q}, {1.0, -0.5}), InvalidArgument);
  EXPECT_THROW(fitBingham({q, q}, {0.0, 0.0}), InvalidArgument);
  EXPECT_THROW(fitBingham({q, q}, {1.0, NAN}), InvalidArgument);
  EXPECT_THROW(fitBingham({q, Eigen::Vector4d::Zero()}), InvalidArgument);
  EXPECT_THROW(fitBingham({q, Eigen::Vector4d(NAN, 0, 0, 1)}), InvalidArgument);
  EXPECT_THROW(makeBingham(2.0 * Eigen::Matrix4d::Identity(), Eigen::Vector4d::Zero()),
               InvalidArgument);
  EXPECT_THROW(makeBingham(Eigen::Matrix4d::Identity(), Eigen::Vector4d(0, 0, NAN, 0)),
               InvalidArgument);
  EXPECT_THROW(binghamNormalizer(Eigen::Vector4d(0, INFINITY, 0, 0)), InvalidArgument);
  // a zero-weight sample does not count, even if it is the only different one
  const Eigen::Vector4d p = Eigen::Vector4d(0, 1, 0, 0);
  EXPECT_LT((fitBingham({q, p}, {1.0, 0.0}).mode() - q).norm(), 1e-12);
}
