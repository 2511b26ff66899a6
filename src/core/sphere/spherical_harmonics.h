/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace pcl::phaser {

/** \brief Spherical harmonic coefficients of a real function at bandwidth B:
 *  F(l, m) = f_l^m for 0 <= m <= l < B (the upper triangle is unused and zero).
 *  Negative orders follow from F(l, -m) = (-1)^m conj(F(l, m)). */
using SphericalSpectrum = Eigen::MatrixXcd;

/** \brief Orthonormal associated Legendre functions with the Condon-Shortley phase,
 *  Pbar_l^m(x), so that Y_l^m = Pbar_l^m(cos theta) e^{i m phi} is orthonormal on S^2.
 *  Evaluated for 0 <= m <= l < B by a log-space start and the three-term recurrence
 *  (accurate up to B = 256).
 * \param[in] bandwidth B
 * \param[in] x the argument cos(theta), in [-1, 1]
 * \return values at index legendreIndex(l, m, B)
 */
std::vector<double> normalizedLegendre(int bandwidth, double x);

/** \brief Position of (l, m) in the packed arrays: column-major in m, l = m..B-1. */
inline int legendreIndex(int l, int m, int bandwidth)
{
  // Offset of column m is sum_{k<m} (B - k) = m B - m (m - 1) / 2.
  return m * bandwidth - m * (m - 1) / 2 + (l - m);
}

/** \brief Number of (l, m) pairs with 0 <= m <= l < B. */
inline int legendreCount(int bandwidth)
{
  return bandwidth * (bandwidth + 1) / 2;
}

/** \brief Squared L2 norm of the real function with spectrum \a F:
 *  sum_l |F(l,0)|^2 + 2 sum_{m>=1} |F(l,m)|^2. */
double spectrumSquaredNorm(const SphericalSpectrum& F);

/** \brief Forward and inverse spherical harmonic transform of real functions sampled
 *  on the Driscoll-Healy grid. Tables and FFTW plans are built once per bandwidth
 *  (instance() shares them); all methods are const and thread-safe. */
class SphericalHarmonicTransform {
public:
  /** \brief Shared instance for \a bandwidth, built on first use (thread-safe).
   *  \throws InvalidArgument unless 1 <= bandwidth <= 256. */
  static std::shared_ptr<const SphericalHarmonicTransform> instance(int bandwidth);

  /** \throws InvalidArgument unless 1 <= bandwidth <= 256. */
  explicit SphericalHarmonicTransform(int bandwidth);
  ~SphericalHarmonicTransform();
  SphericalHarmonicTransform(const SphericalHarmonicTransform&) = delete;
  SphericalHarmonicTransform& operator=(const SphericalHarmonicTransform&) = delete;

  int bandwidth() const { return bandwidth_; }

  /** \brief Coefficients of the real function given by its 4B^2 grid samples
   *  (row-major, one row per ring).
   *  \param[in] num_threads threads for bandwidths of 128 and above (smaller transforms
   *  run on the calling thread); the result does not depend on it. */
  SphericalSpectrum forward(const double* samples, int num_threads = 1) const;

  /** \brief Grid samples (4B^2, row-major) of the band-limited function with spectrum
   * F. */
  std::vector<double> inverse(const SphericalSpectrum& F) const;

private:
  int bandwidth_;
  std::vector<double> weights_;  // w_j for j < 2B
  std::vector<double> legendre_; // Pbar_l^m(x_j), j < B: [legendreIndex(l,m) * B + j]
  struct Plans;
  std::unique_ptr<Plans> plans_;
};

} // namespace pcl::phaser
