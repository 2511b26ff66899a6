/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Bingham distribution on unit quaternions (Bingham 1974): the rotational uncertainty
 * of a PHASER correlation peak (Bernreiter et al., RA-L 2021).
 *
 * Quaternions are Eigen::Vector4d in the order (w, x, y, z), Hamilton convention, i.e.
 * Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()) for an Eigen::Quaterniond q; q and -q are
 * the same rotation and have the same Bingham density.
 */
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <random>
#include <vector>

namespace pcl::phaser {

/** \brief Largest |z| that the maximum-likelihood fit returns. 1e6 is an angular
 *  standard deviation of about sqrt(2e-6) rad = 0.08 deg, far below any SO(3) grid
 *  resolution; a single sample (or identical samples) is fitted with this value. */
constexpr double kMaxBinghamConcentration = 1e6;

/** \brief The normalization constant F(Z) = int_{S^3} exp(sum_i z_i x_i^2) dx of a
 *  4-D Bingham distribution (dx: surface measure, area(S^3) = 2 pi^2) and its
 *  derivatives. F depends on the concentrations only, not on the orientation. */
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

/** \brief Exact F(Z), dF/dZ (and optionally the fourth moments) for any real Z.
 *
 *  Method: in Hopf coordinates x = (sqrt(t) cos a, sqrt(t) sin a, sqrt(1-t) cos b,
 *  sqrt(1-t) sin b) the two circle integrals are modified Bessel functions, which
 *  leaves F(Z) = 2 pi^2 int_0^1 e^{t(z1+z2)/2 + (1-t)(z3+z4)/2} I0(t(z1-z2)/2)
 *  I0((1-t)(z3-z4)/2) dt, a smooth 1-D integral of positive terms (likewise for the
 *  derivatives with I1, I2). It is evaluated with exponentially scaled Bessel
 *  functions and adaptive 21-point Gauss-Kronrod quadrature on a mesh graded towards
 *  the boundary layers of width 1/|z|; relative error <= 3e-13 for |z| <= 1e6.
 *  \param[in] z concentrations, any order
 *  \param[in] with_fourth_moments also compute fourth_moments (for Newton's method) */
BinghamNormalizer binghamNormalizer(const Eigen::Vector4d& z,
                                    bool with_fourth_moments = false);

/** \brief Maximum-likelihood concentrations for the scatter eigenvalues \a omega:
 *  the solution of (dF/dz_i)/F = omega_i with z = 0 for the largest omega (Bingham
 *  1974), found by damped Newton on the convex function log F(Z) - omega . Z.
 *  The result has the same order as \a omega and all z in
 *  [-kMaxBinghamConcentration, 0]: eigenvalues below 1 / (2 kMaxBinghamConcentration)
 *  are raised to that value before solving (the MLE is unbounded for omega_i -> 0),
 *  so rank-deficient scatter gives z ~= -kMaxBinghamConcentration in the null space.
 *  Equal omegas give equal z; omega = (1/4, 1/4, 1/4, 1/4) gives Z = 0.
 *  \param[in] omega non-negative, normalized internally to sum 1
 *  \param[out] residual if given, max_i |E[x_i^2] - omega_i| / omega_i over the three
 *  smaller (floored) omegas at the result; < 1e-10 when converged
 *  \throws InvalidArgument on negative or non-finite values or a zero sum */
Eigen::Vector4d binghamMaximumLikelihood(const Eigen::Vector4d& omega,
                                         double* residual = nullptr);

/** \brief Which side the rotation-vector error of tangentCovariance() is taken on. */
enum class TangentFrame {
  kGlobal, ///< R = Exp(e) R_mode, e = Log(R R_mode^T): error in the fixed frame
  kLocal   ///< R = R_mode Exp(e), e = Log(R_mode^T R): error in the frame of the mode
};

/** \brief A Bingham distribution p(q) = exp(sum_i Z_i (M_i^T q)^2) / F on unit
 *  quaternions (w, x, y, z), with respect to the surface measure of S^3.
 *  Invariants (kept by makeBingham() and fitBingham()): M orthonormal, Z ascending with
 *  Z(3) = 0, so the last column of M is the mode; F, dF belong to Z. The default is the
 *  uniform distribution. */
struct BinghamDistribution {
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity(); ///< orientation, columns m_i
  Eigen::Vector4d Z = Eigen::Vector4d::Zero();     ///< concentrations, Z(3) = 0
  double F = 19.739208802178717; ///< normalization constant F(Z) (default 2 pi^2)
  Eigen::Vector4d dF = Eigen::Vector4d::Constant(F / 4.0); ///< dF/dZ

  /** \brief The mode (last column of M), sign chosen so that w >= 0. */
  Eigen::Vector4d mode() const;

  /** \brief Density at \a q (normalized first; q and -q give the same value). */
  double pdf(const Eigen::Vector4d& q) const;

  /** \brief Exact second moment E[q q^T] = M diag(dF / F) M^T (trace 1). */
  Eigen::Matrix4d moment() const;

  /** \brief Exact covariance (rad^2) of the rotation-vector error e of a sample
   *  relative to the mode (its mean is zero by symmetry). With q_e the error
   *  quaternion taken with w >= 0, e = 2 atan2(|v|, w) v / |v|, and the covariance
   *  is V diag(E[theta^2 n_i^2]) V^T, where V holds the vector parts of the error-frame
   *  axes and E[.] is a 2-D integral (S^3 = angle x S^2) evaluated like F. For a
   *  concentrated Bingham it tends to V diag(-2 / Z_i) V^T (e ~= 2 v, var(v_i) ~=
   *  -1/(2 Z_i)); it is not that first-order value for spread-out distributions.
   *  \param[in] frame side of the error, see TangentFrame; local = R_mode^T global
   *  R_mode */
  Eigen::Matrix3d tangentCovariance(TangentFrame frame = TangentFrame::kGlobal) const;

  /** \brief \a n independent samples (unit quaternions, w >= 0) by rejection from an
   *  angular central Gaussian envelope (Kent, Ganeiber & Mardia 2013); deterministic
   *  for a given generator state and standard library. Acceptance rate >= ~50%. */
  std::vector<Eigen::Vector4d> sample(std::size_t n, std::mt19937& rng) const;
};

/** \brief A distribution from any orientation and concentrations: columns are sorted
 *  by ascending z, Z is shifted so that its maximum is 0 (the density is unchanged)
 *  and F, dF are computed. \throws InvalidArgument unless \a M is orthonormal
 *  (tolerance 1e-6) and \a Z finite. */
BinghamDistribution makeBingham(const Eigen::Matrix4d& M, const Eigen::Vector4d& Z);

/** \brief Weighted maximum-likelihood Bingham fit (Bingham 1974): the scatter matrix
 *  S = sum_i w_i q_i q_i^T / sum_i w_i is diagonalized (M = eigenvectors, ascending)
 *  and Z = binghamMaximumLikelihood(eigenvalues). The sign of each q_i is irrelevant.
 *  \param[in] quaternions samples (w, x, y, z); non-unit ones are normalized
 *  \param[in] weights one non-negative weight per sample, or empty for equal weights
 *  \throws InvalidArgument if there are no samples, sizes differ, a weight is
 *  negative or non-finite, the weights sum to zero, or a quaternion is zero or not
 *  finite */
BinghamDistribution fitBingham(const std::vector<Eigen::Vector4d>& quaternions,
                               const std::vector<double>& weights = {});

namespace detail {
/** \brief Exponentially scaled modified Bessel function e^{-x} I_n(x), n in {0, 1, 2},
 *  x >= 0 (power series below 20, asymptotic expansion above); exposed for tests. */
double scaledBesselI(int n, double x);
} // namespace detail

} // namespace pcl::phaser
