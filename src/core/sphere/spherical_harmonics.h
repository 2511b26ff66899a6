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

/** \brief Squared L2 norm of the real function with spectrum \a F:
 *  sum_l |F(l,0)|^2 + 2 sum_{m>=1} |F(l,m)|^2. */
double spectrumSquaredNorm(const SphericalSpectrum& F);

/** \brief Forward (and, for tests, inverse) spherical harmonic transform of real
 *  functions sampled on the Driscoll-Healy grid (doc/so3-correlation-spec.md section
 * 2).
 *
 * The tables (weights, Legendre values for the northern rings) and FFTW plans are built
 * once per bandwidth; use instance() to share them. All methods are const and
 * thread-safe.
 */
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
