/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Independent reference pieces for the SO(3) tests: spherical harmonics evaluated at
 * arbitrary directions, Wigner D, and the plain complex correlation of spec section 3.2
 * (naive separable DFT, no FFTW), against which the fast path is checked.
 */
#pragma once

#include "so3/so3_correlation.h"
#include "so3/so3_correlation_grid.h"
#include "so3/wigner.h"
#include "sphere/spherical_grid.h"
#include "sphere/spherical_harmonics.h"
#include "support/error.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <utility>
#include <vector>

namespace pcl::phaser {
/** Step from degree l to l+1 of the Kostelec-Rockmore recurrence for orders (m', m),
 *  l >= max(|m'|, |m|), computed directly: the reference for WignerStepTable. */
inline WignerStep wignerStep(int l, int mp, int m)
{
  if (l == 0) // only m = m' = 0: d^1_00 = cos(beta)
    return {1.0, 0.0, 0.0};
  const double l1 = l + 1.0;
  const double mm = static_cast<double>(m) * m;
  const double mpmp = static_cast<double>(mp) * mp;
  const double r = std::sqrt((l1 * l1 - mm) * (l1 * l1 - mpmp));
  const double a = l1 * (2.0 * l + 1.0) / r;
  const double cc = -static_cast<double>(m) * mp / (static_cast<double>(l) * l1);
  const double ll = static_cast<double>(l) * l;
  const double b = l1 * std::sqrt(std::max(0.0, (ll - mm) * (ll - mpmp))) / (l * r);
  return {a, a * cc, b};
}

/** d^l_{m'm}(beta) (Wigner/Sakurai convention, |d| <= 1) for l = 0..B-1 by the direct
 *  recurrence; entries with l < max(|m'|,|m|) are zero. beta in [0, pi]. */
inline std::vector<double> wignerSmallD(int mp, int m, int bandwidth, double beta)
{
  checkBandwidth(bandwidth);
  std::vector<double> d(bandwidth, 0.0);
  const int L = std::max(std::abs(mp), std::abs(m));
  if (L >= bandwidth)
    return d;
  const std::vector<double> lf = logFactorials(2 * L + 1);
  const WignerStart start = wignerStart(mp, m, lf);
  const double cb = std::cos(beta);
  double prev =
      start.value(std::log(std::cos(0.5 * beta)), std::log(std::sin(0.5 * beta)));
  double prev2 = 0.0;
  for (int l = L; l < bandwidth; ++l) {
    d[l] = prev;
    const WignerStep st = wignerStep(l, mp, m);
    const double next = (st.a * cb + st.ac) * prev - st.b * prev2;
    prev2 = prev;
    prev = next;
  }
  return d;
}

/** Exact C(R) of one spectrum pair at arbitrary rotations (evaluateCorrelations). */
inline std::vector<double>
evaluateCorrelation(const SphericalSpectrum& target, const SphericalSpectrum& source,
                    const std::vector<Eigen::Matrix3d>& rotations, int num_threads = 1)
{
  return std::move(
      evaluateCorrelations({SpectrumPair{&target, &source}}, rotations, num_threads)
          .front());
}

namespace test {

using Complex = std::complex<double>;

/** F(l, m) for any order of a real function's spectrum. */
inline Complex coef(const SphericalSpectrum& F, int l, int m)
{
  if (m >= 0)
    return F(l, m);
  const Complex c = std::conj(F(l, -m));
  return (m % 2) ? -c : c;
}

/** Y_l^m(direction) for all l < B and -l <= m <= l, as Y[l][m + l]. */
inline std::vector<std::vector<Complex>> sphericalHarmonics(int B,
                                                            const Eigen::Vector3d& dir)
{
  const double theta = std::atan2(std::hypot(dir.x(), dir.y()), dir.z());
  const double phi = std::atan2(dir.y(), dir.x());
  const std::vector<double> p = normalizedLegendre(B, std::cos(theta));
  std::vector<std::vector<Complex>> Y(B);
  for (int l = 0; l < B; ++l) {
    Y[l].resize(2 * l + 1);
    for (int m = 0; m <= l; ++m) {
      const Complex y = p[legendreIndex(l, m, B)] * std::polar(1.0, m * phi);
      Y[l][l + m] = y;
      Y[l][l - m] = ((m % 2) ? -1.0 : 1.0) * std::conj(y);
    }
  }
  return Y;
}

/** Value of the real band-limited function with spectrum F at a direction. */
inline double synthesize(const SphericalSpectrum& F, const Eigen::Vector3d& dir)
{
  const int B = static_cast<int>(F.rows());
  const auto Y = sphericalHarmonics(B, dir);
  double v = 0.0;
  for (int l = 0; l < B; ++l)
    for (int m = -l; m <= l; ++m)
      v += (coef(F, l, m) * Y[l][l + m]).real();
  return v;
}

/** Random spectrum of a real function (F(l,0) real). */
inline SphericalSpectrum randomSpectrum(int B, std::mt19937& rng)
{
  std::normal_distribution<double> n01;
  SphericalSpectrum F = SphericalSpectrum::Zero(B, B);
  for (int l = 0; l < B; ++l) {
    F(l, 0) = n01(rng);
    for (int m = 1; m <= l; ++m)
      F(l, m) = Complex(n01(rng), n01(rng));
  }
  return F;
}

/** D^l_{m'm}(R) = e^{-i m' alpha} d^l_{m'm}(beta) e^{-i m gamma}. */
inline Complex wignerD(int l, int mp, int m, const EulerZYZ& e)
{
  const double d = wignerSmallD(mp, m, l + 1, e.beta)[l];
  return std::polar(1.0, -mp * e.alpha) * d * std::polar(1.0, -m * e.gamma);
}

/** Spectrum of f = Lambda(R) h, i.e. f(w) = h(R^-1 w): f_l^{m'} = sum_m D^l_{m'm}(R)
 * h_l^m. */
inline SphericalSpectrum rotateSpectrum(const SphericalSpectrum& H,
                                        const Eigen::Matrix3d& R)
{
  const int B = static_cast<int>(H.rows());
  const EulerZYZ e = eulerFromRotation(R);
  SphericalSpectrum F = SphericalSpectrum::Zero(B, B);
  for (int l = 0; l < B; ++l)
    for (int mp = 0; mp <= l; ++mp) {
      Complex v = 0.0;
      for (int m = -l; m <= l; ++m)
        v += wignerD(l, mp, m, e) * coef(H, l, m);
      F(l, mp) = v;
    }
  return F;
}

/** Spec section 3.2: full complex S_j(m', m) for every beta_j, then the forward 2-D DFT
 *  (e^{-i}), done as a naive separable sum. Returns C[(j*N + a)*N + c]. */
inline std::vector<double> referenceCorrelation(const SphericalSpectrum& F,
                                                const SphericalSpectrum& H, int Bo)
{
  const int B = static_cast<int>(F.rows());
  const int N = 2 * Bo;
  const int M = 2 * B - 1; // orders -(B-1)..(B-1)
  std::vector<double> C(static_cast<std::size_t>(N) * N * N);
  std::vector<Complex> S(M * M), P(M * N);
  for (int j = 0; j < N; ++j) {
    const double beta = M_PI * (2 * j + 1) / (4.0 * Bo);
    for (int mp = -(B - 1); mp < B; ++mp)
      for (int m = -(B - 1); m < B; ++m) {
        const std::vector<double> d = wignerSmallD(mp, m, B, beta);
        Complex s = 0.0;
        for (int l = std::max(std::abs(mp), std::abs(m)); l < B; ++l)
          s += std::conj(coef(F, l, mp)) * coef(H, l, m) * d[l];
        S[(mp + B - 1) * M + (m + B - 1)] = s;
      }
    for (int mp = 0; mp < M; ++mp) // sum over m for every gamma_c
      for (int c = 0; c < N; ++c) {
        Complex v = 0.0;
        for (int m = 0; m < M; ++m)
          v += S[mp * M + m] * std::polar(1.0, -(m - (B - 1)) * 2.0 * M_PI * c / N);
        P[mp * N + c] = v;
      }
    for (int a = 0; a < N; ++a)
      for (int c = 0; c < N; ++c) {
        Complex v = 0.0;
        for (int mp = 0; mp < M; ++mp)
          v += P[mp * N + c] * std::polar(1.0, -(mp - (B - 1)) * 2.0 * M_PI * a / N);
        C[(static_cast<std::size_t>(j) * N + a) * N + c] = v.real();
      }
  }
  return C;
}

/** Samples of h(w) = sum_i exp(kappa (w . p_i - 1)) on the grid: a nearly band-limited
 *  function with sharp lobes at the unit directions p_i. */
inline std::vector<double> lobeSamples(int B, const std::vector<Eigen::Vector3d>& dirs,
                                       const std::vector<double>& w, double kappa)
{
  const int n = 2 * B;
  std::vector<double> f(static_cast<std::size_t>(n) * n, 0.0);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d omega = sampleDirection(j, k, B);
      double v = 0.0;
      for (std::size_t i = 0; i < dirs.size(); ++i)
        v += w[i] * std::exp(kappa * (omega.dot(dirs[i]) - 1.0));
      f[j * n + k] = v;
    }
  return f;
}

inline Eigen::Matrix3d randomRotation(std::mt19937& rng)
{
  std::normal_distribution<double> n01;
  Eigen::Quaterniond q(n01(rng), n01(rng), n01(rng), n01(rng));
  return q.normalized().toRotationMatrix();
}

} // namespace test
} // namespace pcl::phaser
