/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "support/error.h"

#include <pcl_phaser/core/bingham.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>

namespace pcl::phaser {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPiSquared = 2.0 * kPi * kPi;
/** GK21 |Kronrod - Gauss| overestimates the error of smooth integrands: this gives
 *  ~1e-13 actual relative error. */
constexpr double kQuadratureTolerance = 1e-11;
constexpr std::size_t kMaxPieces = 4000;

/** sum_n c(n) e^{-x} I_n(x) (n = 0, 1, 2, x >= 0) for the six rows of \a c, each as one
 *  series, so differences such as I0 - I1 ~ I0 / 2x do not cancel for large x. */
std::array<double, 6> besselCombos(double x, const double (&c)[6][3])
{
  std::array<double, 6> out{};
  if (x < 20.0) {
    // Power series I_n(x) = sum_k (x/2)^{2k+n} / (k! (k+n)!); the differences lose
    // < 3 digits below x = 20.
    double in[3];
    const double h = 0.5 * x, h2 = h * h;
    for (int n = 0; n < 3; ++n) {
      double term = n == 0 ? 1.0 : (n == 1 ? h : 0.5 * h2), sum = term;
      for (int k = 1; k < 200 && term > 1e-17 * sum; ++k) {
        term *= h2 / (k * double(k + n));
        sum += term;
      }
      in[n] = sum * std::exp(-x);
    }
    for (int r = 0; r < 6; ++r)
      out[r] = c[r][0] * in[0] + c[r][1] * in[1] + c[r][2] * in[2];
    return out;
  }
  // Asymptotic expansion e^{-x} I_n(x) ~ (2 pi x)^{-1/2} sum_k (-1)^k a_k(n) / x^k,
  // a_k(n) = prod_{j<=k} (4n^2 - (2j-1)^2) / (k! 8^k), combined term by term.
  double a[3] = {1.0, 1.0, 1.0}, power = 1.0;
  std::array<double, 6> sum{};
  for (int k = 0; k < 2 * int(x) + 2 && k < 120; ++k) {
    if (k > 0) {
      for (int n = 0; n < 3; ++n)
        a[n] *= (4.0 * n * n - (2.0 * k - 1) * (2.0 * k - 1)) / (8.0 * k);
      power *= -1.0 / x;
    }
    bool converged = k > 3;
    for (int r = 0; r < 6; ++r) {
      const double term = power * (c[r][0] * a[0] + c[r][1] * a[1] + c[r][2] * a[2]);
      sum[r] += term;
      converged = converged && std::abs(term) <= 1e-17 * std::abs(sum[r]);
    }
    if (converged)
      break;
  }
  const double scale = 1.0 / std::sqrt(2.0 * kPi * x);
  for (int r = 0; r < 6; ++r)
    out[r] = sum[r] * scale;
  return out;
}

/** int_0^{2pi} g(al) e^{a cos^2 al + b sin^2 al} dal / (2 pi e^{max(a,b)}) for g = 1,
 *  cos^2, sin^2, cos^4, sin^4, cos^2 sin^2: Bessel combinations of u = |a - b| / 2. */
struct CircleMoments {
  double one, cos2, sin2, cos4, sin4, cos2sin2;
};

CircleMoments circleMoments(double a, double b)
{
  static const double kCombos[6][3] = {{1, 0, 0},
                                       {0.5, 0.5, 0},
                                       {0.5, -0.5, 0},
                                       {3. / 8, 0.5, 1. / 8},
                                       {3. / 8, -0.5, 1. / 8},
                                       {1. / 8, 0, -1. / 8}};
  // For b > a swap the roles of cos and sin (al -> pi/2 - al) so that u >= 0.
  const bool swap = b > a;
  const std::array<double, 6> v = besselCombos(0.5 * std::abs(a - b), kCombos);
  if (swap)
    return {v[0], v[2], v[1], v[4], v[3], v[5]};
  return {v[0], v[1], v[2], v[3], v[4], v[5]};
}

/** Breakpoints of [a, b] graded geometrically (ratio 4) towards both ends down to
 *  \a width * (b - a): the integrands have boundary layers of width ~1/|z|. */
std::vector<double> gradedMesh(double a, double b, double width)
{
  std::vector<double> lo{a, 0.5 * (a + b)}, hi{b};
  for (double h = 0.25; h > 0.25 * width; h *= 0.25) {
    lo.push_back(a + h * (b - a));
    hi.push_back(b - h * (b - a));
  }
  lo.insert(lo.end(), hi.begin(), hi.end());
  std::sort(lo.begin(), lo.end());
  return lo;
}

/** Globally adaptive 21-point Gauss-Kronrod quadrature of a vector integrand with
 *  non-negative components: the piece of largest relative error is bisected until
 *  every component meets kQuadratureTolerance. */
template <int K, class Integrand>
Eigen::Matrix<double, K, 1> integrate(const Integrand& fn,
                                      const std::vector<double>& breaks)
{
  using Vec = Eigen::Matrix<double, K, 1>;
  using Kronrod = boost::math::quadrature::gauss_kronrod<double, 21>;
  using Gauss = boost::math::quadrature::gauss<double, 10>;
  struct Piece {
    double a, b;
    Vec value, error;
  };
  const auto rule = [&](double a, double b) {
    const double c = 0.5 * (a + b), h = 0.5 * (b - a);
    const auto& x = Kronrod::abscissa();
    const auto& wk = Kronrod::weights();
    const auto& wg = Gauss::weights();
    const Vec f0 = fn(c);
    Vec kronrod = wk[0] * f0, gauss = Vec::Zero();
    for (std::size_t i = 1; i < x.size(); ++i) {
      const Vec f = fn(c - h * x[i]) + fn(c + h * x[i]);
      kronrod += wk[i] * f;
      if (i % 2 == 1) // the odd Kronrod nodes are the 10 Gauss nodes
        gauss += wg[i / 2] * f;
    }
    return Piece{a, b, h * kronrod, h * (kronrod - gauss).cwiseAbs()};
  };
  std::vector<Piece> pieces;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i)
    pieces.push_back(rule(breaks[i], breaks[i + 1]));
  Vec total;
  while (true) {
    total.setZero();
    Vec error = Vec::Zero();
    for (const Piece& p : pieces) {
      total += p.value;
      error += p.error;
    }
    if ((error.array() <= kQuadratureTolerance * total.array().abs()).all() ||
        pieces.size() >= kMaxPieces)
      return total;
    const Vec scale = total.cwiseAbs().cwiseMax(1e-300).cwiseInverse();
    std::size_t worst = 0;
    double worst_error = -1.0;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const double e = pieces[i].error.cwiseProduct(scale).maxCoeff();
      if (e > worst_error) {
        worst_error = e;
        worst = i;
      }
    }
    const double a = pieces[worst].a, b = pieces[worst].b, m = 0.5 * (a + b);
    pieces[worst] = rule(a, m);
    pieces.push_back(rule(m, b));
  }
}

Eigen::Quaterniond toQuaternion(const Eigen::Vector4d& q)
{
  return Eigen::Quaterniond(q(0), q(1), q(2), q(3));
}

} // namespace

namespace detail {
double scaledBesselI(int n, double x)
{
  if (n < 0 || n > 2 || !(x >= 0.0))
    throw InvalidArgument("scaledBesselI: need n in {0, 1, 2} and x >= 0");
  const double c[6][3] = {{n == 0 ? 1.0 : 0.0, n == 1 ? 1.0 : 0.0, n == 2 ? 1.0 : 0.0}};
  return besselCombos(x, c)[0];
}
} // namespace detail

BinghamNormalizer binghamNormalizer(const Eigen::Vector4d& z, bool with_fourth_moments)
{
  if (!z.allFinite())
    throw InvalidArgument("binghamNormalizer: concentrations must be finite");
  // Hopf coordinates: the two most concentrated directions on the circle of radius
  // sqrt(t), the other two on radius sqrt(1 - t).
  std::array<int, 4> idx{0, 1, 2, 3};
  std::sort(idx.begin(), idx.end(), [&](int i, int j) { return z(i) < z(j); });
  const double z_max = z(idx[3]);
  const double a0 = z(idx[0]) - z_max, a1 = z(idx[1]) - z_max;
  const double b0 = z(idx[2]) - z_max; // b1 = 0 after the shift
  // dx = (1/2) dt dal dbe, so F = 2 pi^2 int_0^1 e^{t a1} P(t) Q(t) dt with the circle
  // moments P, Q; x_i^2 brings t cos^2 al etc.
  using Vec15 = Eigen::Matrix<double, 15, 1>;
  const auto integrand = [&](double t) {
    const double s = 1.0 - t, e = std::exp(t * a1);
    const CircleMoments p = circleMoments(t * a0, t * a1);
    const CircleMoments q = circleMoments(s * b0, 0.0);
    Vec15 v;
    v << p.one * q.one, t * p.cos2 * q.one, t * p.sin2 * q.one, s * p.one * q.cos2,
        s * p.one * q.sin2, // F, dF in sorted order
        t * t * p.cos4 * q.one, t * t * p.cos2sin2 * q.one, t * s * p.cos2 * q.cos2,
        t * s * p.cos2 * q.sin2, t * t * p.sin4 * q.one, t * s * p.sin2 * q.cos2,
        t * s * p.sin2 * q.sin2, s * s * p.one * q.cos4, s * s * p.one * q.cos2sin2,
        s * s * p.one * q.sin4; // upper triangle of d2F, row by row
    return Vec15(e * v);
  };
  const std::vector<double> mesh = gradedMesh(0.0, 1.0, 1.0 / (1.0 - a0));
  Vec15 integral;
  if (with_fourth_moments)
    integral = integrate<15>(integrand, mesh);
  else
    integral.head<5>() = integrate<5>(
        [&](double t) { return Eigen::Matrix<double, 5, 1>(integrand(t).head<5>()); },
        mesh);

  BinghamNormalizer out;
  out.log_f = std::log(kTwoPiSquared * integral(0)) + z_max;
  out.f = std::exp(out.log_f);
  for (int i = 0; i < 4; ++i) {
    out.moments(idx[i]) = integral(1 + i) / integral(0);
    out.df(idx[i]) = out.moments(idx[i]) * out.f;
  }
  if (with_fourth_moments)
    for (int i = 0, k = 5; i < 4; ++i)
      for (int j = i; j < 4; ++j, ++k)
        out.fourth_moments(idx[i], idx[j]) = out.fourth_moments(idx[j], idx[i]) =
            integral(k) / integral(0);
  return out;
}

namespace {

/** F and its moments at Z = (y, 0), with the fourth moments Newton needs. */
BinghamNormalizer normalizerAt(const Eigen::Vector3d& y)
{
  return binghamNormalizer(Eigen::Vector4d(y(0), y(1), y(2), 0.0), true);
}

/** One damped Newton step on the convex L(y) = log F(y, 0) - w . (y, 0) from (\a y,
 *  its \a normalizer), whose gradient is \a g = E[x^2] - w and Hessian
 *  Cov(x_i^2, x_j^2) = E[x_i^2 x_j^2] - E[x_i^2] E[x_j^2]; the step is halved until
 *  Armijo holds. False, with \a y and \a normalizer unchanged, when no length is
 * accepted. */
bool dampedNewtonStep(const Eigen::Vector4d& w, const Eigen::Vector3d& g,
                      Eigen::Vector3d& y, BinghamNormalizer& normalizer)
{
  const Eigen::Vector3d m = normalizer.moments.head<3>();
  const Eigen::Matrix3d h =
      normalizer.fourth_moments.topLeftCorner<3, 3>() - m * m.transpose();
  // Jacobi scaling: the diagonal spans ~1/(2 z^2), i.e. many orders of magnitude.
  const Eigen::Vector3d d = h.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::Matrix3d hs = d.asDiagonal() * h * d.asDiagonal();
  const Eigen::Vector3d step = -d.cwiseProduct(hs.ldlt().solve(d.cwiseProduct(g)));
  const double l0 = normalizer.log_f - w.head<3>().dot(y), slope = g.dot(step);
  for (double alpha = 1.0; alpha > 1e-12; alpha *= 0.5) {
    const Eigen::Vector3d y_new = y + alpha * step;
    const BinghamNormalizer n_new = normalizerAt(y_new);
    const double l_new = n_new.log_f - w.head<3>().dot(y_new);
    // Armijo, with slack for the ~1e-13 rounding of log F near the optimum.
    if (l_new <= l0 + 1e-4 * alpha * slope + 1e-13 * (1.0 + std::abs(l0))) {
      y = y_new;
      normalizer = n_new;
      return true;
    }
  }
  return false;
}

} // namespace

Eigen::Vector4d binghamMaximumLikelihood(const Eigen::Vector4d& omega, double* residual)
{
  if (!omega.allFinite() || (omega.array() < 0.0).any() || omega.sum() <= 0.0)
    throw InvalidArgument("binghamMaximumLikelihood: omega must be finite, >= 0 and "
                          "not all zero");
  std::array<int, 4> idx{0, 1, 2, 3};
  std::stable_sort(idx.begin(), idx.end(),
                   [&](int i, int j) { return omega(i) < omega(j); });
  Eigen::Vector4d w;
  for (int i = 0; i < 4; ++i)
    w(i) = omega(idx[i]) / omega.sum();
  // omega_i -> 0 has z_i -> -infinity; asymptotically E[x_i^2] = -1/(2 z_i), so this
  // floor keeps the solution within the cap.
  const double floor = 0.5 / kMaxBinghamConcentration;
  w.head<3>() = w.head<3>().cwiseMax(floor);
  w /= w.sum();

  // Newton from the concentrated asymptotics, shifted so that equal omegas start at
  // z = 0.
  Eigen::Vector3d y;
  for (int i = 0; i < 3; ++i)
    y(i) = std::min(0.0, 0.5 / w(3) - 0.5 / w(i));
  BinghamNormalizer normalizer = normalizerAt(y);
  double res = 0.0;
  for (int iter = 0; iter < 200; ++iter) {
    const Eigen::Vector3d g = normalizer.moments.head<3>() - w.head<3>();
    res = g.cwiseQuotient(w.head<3>()).cwiseAbs().maxCoeff();
    if (res < 1e-10 || !dampedNewtonStep(w, g, y, normalizer))
      break;
  }
  if (residual)
    *residual = res;
  Eigen::Vector4d z = Eigen::Vector4d::Zero();
  for (int i = 0; i < 3; ++i)
    z(idx[i]) = std::clamp(y(i), -kMaxBinghamConcentration, 0.0);
  return z;
}

Eigen::Vector4d BinghamDistribution::mode() const
{
  const Eigen::Vector4d m = M.col(3);
  return m(0) < 0.0 ? Eigen::Vector4d(-m) : m;
}

double BinghamDistribution::pdf(const Eigen::Vector4d& q) const
{
  const Eigen::Vector4d x = M.transpose() * q.normalized();
  return std::exp(Z.dot(x.cwiseAbs2())) / F;
}

Eigen::Matrix4d BinghamDistribution::moment() const
{
  return M * (dF / F).asDiagonal() * M.transpose();
}

Eigen::Matrix3d BinghamDistribution::tangentCovariance(TangentFrame frame) const
{
  // Error quaternion (cos psi, sin psi n) in the error frame, a_i = Z_i - Z_3, angle
  // 2 psi: c_i = E[theta^2 n_i^2] = int_0^{pi/2} 4 psi^2 sin^2 psi G_i dpsi / int
  // sin^2 psi G, G_i(s) = int_{S^2} n_i^2 exp(s sum a_j n_j^2) dn, a 1-D integral over
  // the height v of n, scaled by e^{-s max a}.
  const Eigen::Vector3d a = Z.head<3>().array() - Z(3);
  const double a_max = a.maxCoeff(), a_min = a.minCoeff();
  using Vec4 = Eigen::Matrix<double, 4, 1>;
  const auto sphere = [&](double s) {
    const auto inner = [&](double v) {
      const double r2 = 1.0 - v * v, top = std::max(a(0), a(1));
      const CircleMoments p = circleMoments(s * r2 * a(0), s * r2 * a(1));
      const double e = std::exp(s * (a(2) * v * v + r2 * top - a_max));
      return Vec4(e * Vec4(p.one, r2 * p.cos2, r2 * p.sin2, v * v * p.one));
    };
    return integrate<4>(inner, gradedMesh(0.0, 1.0, 1.0 / (1.0 - s * a_min)));
  };
  const auto outer = [&](double psi) {
    const double s = std::sin(psi) * std::sin(psi);
    const Vec4 g = sphere(s) * (s * std::exp(s * a_max));
    return Vec4(g(0), 4 * psi * psi * g(1), 4 * psi * psi * g(2), 4 * psi * psi * g(3));
  };
  const Vec4 r =
      integrate<4>(outer, gradedMesh(0.0, 0.5 * kPi, 1.0 / std::sqrt(1.0 - a_min)));
  const Eigen::Quaterniond p_conj = toQuaternion(M.col(3)).conjugate();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const Eigen::Quaterniond m = toQuaternion(M.col(i));
    const Eigen::Vector3d v =
        (frame == TangentFrame::kGlobal ? m * p_conj : p_conj * m).vec();
    cov += (r(1 + i) / r(0)) * v * v.transpose();
  }
  return cov;
}

BinghamDistribution makeBingham(const Eigen::Matrix4d& M, const Eigen::Vector4d& Z)
{
  if (!Z.allFinite() || !M.allFinite() ||
      !(M.transpose() * M).isApprox(Eigen::Matrix4d::Identity(), 1e-6))
    throw InvalidArgument("makeBingham: M must be orthonormal and Z finite");
  std::array<int, 4> idx{0, 1, 2, 3};
  std::stable_sort(idx.begin(), idx.end(), [&](int i, int j) { return Z(i) < Z(j); });
  BinghamDistribution d;
  for (int i = 0; i < 4; ++i) {
    d.M.col(i) = M.col(idx[i]);
    d.Z(i) = Z(idx[i]) - Z(idx[3]);
  }
  if (d.M(0, 3) < 0.0) // canonical mode sign (w >= 0); the density is unchanged
    d.M.col(3) *= -1.0;
  const BinghamNormalizer n = binghamNormalizer(d.Z);
  d.F = n.f;
  d.dF = n.df;
  return d;
}

BinghamDistribution fitBingham(const std::vector<Eigen::Vector4d>& quaternions,
                               const std::vector<double>& weights)
{
  if (quaternions.empty())
    throw InvalidArgument("fitBingham: no samples");
  if (!weights.empty() && weights.size() != quaternions.size())
    throw InvalidArgument("fitBingham: " + std::to_string(weights.size()) +
                          " weights for " + std::to_string(quaternions.size()) +
                          " quaternions");
  Eigen::Matrix4d scatter = Eigen::Matrix4d::Zero();
  double total = 0.0;
  for (std::size_t i = 0; i < quaternions.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    const double norm = quaternions[i].norm();
    if (!std::isfinite(w) || w < 0.0)
      throw InvalidArgument("fitBingham: weights must be finite and non-negative");
    if (!std::isfinite(norm) || norm == 0.0)
      throw InvalidArgument("fitBingham: quaternions must be finite and non-zero");
    const Eigen::Vector4d q = quaternions[i] / norm;
    scatter += w * q * q.transpose();
    total += w;
  }
  if (!(total > 0.0))
    throw InvalidArgument("fitBingham: the weights sum to zero");
  // The symmetric solver returns ascending eigenvalues with orthonormal eigenvectors.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(scatter / total);
  const Eigen::Vector4d omega = eig.eigenvalues().cwiseMax(0.0);
  return makeBingham(eig.eigenvectors(), binghamMaximumLikelihood(omega));
}

} // namespace pcl::phaser
