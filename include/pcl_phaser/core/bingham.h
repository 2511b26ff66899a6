/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Bingham distribution (Bingham 1974) on unit quaternions, Eigen::Vector4d (w, x, y,
 * z), Hamilton convention; q and -q have the same density.
 */
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl::phaser {

/** \brief Largest |z| the maximum-likelihood fit returns (a single sample gets it):
 *  an angular standard deviation of about 0.08 deg. */
constexpr double kMaxBinghamConcentration = 1e6;

/** \brief The normalization constant F(Z) = int_{S^3} exp(sum_i z_i x_i^2) dx (surface
 *  measure, area 2 pi^2) of a 4-D Bingham distribution and its derivatives. */
struct BinghamNormalizer {
  double log_f = 0.0; ///< log F(Z)
  double f = 0.0;     ///< F(Z) = exp(log_f); inf if max z > ~700
  Eigen::Vector4d df = Eigen::Vector4d::Zero(); ///< dF/dz_i (inf where f is)
  /** \brief E[x_i^2] = (dF/dz_i) / F; sums to 1; no overflow. */
  Eigen::Vector4d moments = Eigen::Vector4d::Zero();
  /** \brief E[x_i^2 x_j^2] = (d^2F/dz_i dz_j) / F (only if requested, else zero);
   *  row i sums to moments(i). */
  Eigen::Matrix4d fourth_moments = Eigen::Matrix4d::Zero();
};

/** \brief Exact F(Z), dF/dZ (and optionally the fourth moments) for any real \a z, in
 *  any order; relative error <= 3e-13 for |z| <= 1e6. */
BinghamNormalizer binghamNormalizer(const Eigen::Vector4d& z,
                                    bool with_fourth_moments = false);

/** \brief Maximum-likelihood concentrations for the scatter eigenvalues \a omega
 *  (non-negative, normalized to sum 1): (dF/dz_i)/F = omega_i, z = 0 for the largest
 *  omega. Same order as \a omega, all z in [-kMaxBinghamConcentration, 0]; equal
 *  omegas give equal z.
 *  \param[out] residual if given, max_i |E[x_i^2] - omega_i| / omega_i over the three
 *  smaller omegas; < 1e-10 when converged
 *  \throws InvalidArgument on negative or non-finite values or a zero sum */
Eigen::Vector4d binghamMaximumLikelihood(const Eigen::Vector4d& omega,
                                         double* residual = nullptr);

/** \brief Which side the rotation-vector error of tangentCovariance() is taken on. */
enum class TangentFrame {
  kGlobal, ///< R = Exp(e) R_mode, e = Log(R R_mode^T): error in the fixed frame
  kLocal   ///< R = R_mode Exp(e), e = Log(R_mode^T R): error in the frame of the mode
};

/** \brief A Bingham distribution p(q) = exp(sum_i Z_i (M_i^T q)^2) / F on unit
 *  quaternions (w, x, y, z). makeBingham() and fitBingham() keep M orthonormal and Z
 *  ascending with Z(3) = 0 (the last column of M is the mode). Default: uniform. */
struct BinghamDistribution {
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity(); ///< orientation, columns m_i
  Eigen::Vector4d Z = Eigen::Vector4d::Zero();     ///< concentrations, Z(3) = 0
  double F = 19.739208802178717; ///< normalization constant F(Z) (default 2 pi^2)
  Eigen::Vector4d dF = Eigen::Vector4d::Constant(F / 4.0); ///< dF/dZ

  /** \brief The mode (last column of M), sign chosen so that w >= 0. */
  Eigen::Vector4d mode() const;

  /** \brief Density at \a q (normalized first). */
  double pdf(const Eigen::Vector4d& q) const;

  /** \brief Exact second moment E[q q^T] = M diag(dF / F) M^T (trace 1). */
  Eigen::Matrix4d moment() const;

  /** \brief Exact covariance (rad^2) of the rotation-vector error e = 2 atan2(|v|, w)
   *  v / |v| of a sample's error quaternion (w >= 0) relative to the mode.
   *  \param[in] frame side of the error; local = R_mode^T global R_mode */
  Eigen::Matrix3d tangentCovariance(TangentFrame frame = TangentFrame::kGlobal) const;
};

/** \brief A distribution from any orientation and concentrations, sorted by ascending z
 *  and shifted to max z = 0. \throws InvalidArgument unless \a M is orthonormal (to
 *  1e-6) and \a Z finite. */
BinghamDistribution makeBingham(const Eigen::Matrix4d& M, const Eigen::Vector4d& Z);

/** \brief Weighted maximum-likelihood fit (Bingham 1974): M = eigenvectors of the
 *  scatter sum_i w_i q_i q_i^T / sum_i w_i, Z = binghamMaximumLikelihood(eigenvalues).
 *  \param[in] quaternions samples (w, x, y, z), normalized; their sign is irrelevant
 *  \param[in] weights one non-negative weight per sample, or empty for equal weights
 *  \throws InvalidArgument for no samples, mismatched sizes, a negative or non-finite
 *  weight, a zero weight sum, or a zero or non-finite quaternion */
BinghamDistribution fitBingham(const std::vector<Eigen::Vector4d>& quaternions,
                               const std::vector<double>& weights = {});

namespace detail {
/** \brief e^{-x} I_n(x) (modified Bessel), n in {0, 1, 2}, x >= 0; for tests. */
double scaledBesselI(int n, double x);
} // namespace detail

} // namespace pcl::phaser
