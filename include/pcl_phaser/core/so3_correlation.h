/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/core/so3_grid.h>
#include <pcl_phaser/core/spherical_harmonics.h>
#include <pcl_phaser/core/wigner.h>

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <vector>

namespace pcl::phaser {

/** \brief The correlation C(R) = int f(w) h(R^-1 w) dw sampled on the (2Bo)^3 Euler
 * grid (f = target, h = source). Owns its buffer; cheap to move. */
class So3CorrelationGrid {
public:
  So3CorrelationGrid() = default;
  So3CorrelationGrid(So3CorrelationGrid&&) noexcept;
  So3CorrelationGrid& operator=(So3CorrelationGrid&&) noexcept;
  ~So3CorrelationGrid();

  int outputBandwidth() const { return output_bandwidth_; }
  /** \brief Samples per axis, N = 2 Bo. */
  int size() const { return 2 * output_bandwidth_; }

  /** \brief C(alpha_a, beta_j, gamma_c); -infinity for rows j >= betaRows(). */
  double operator()(int j, int a, int c) const
  {
    if (j >= beta_rows_)
      return -std::numeric_limits<double>::infinity();
    return data_[(static_cast<std::size_t>(j) * size() + a) * row_stride_ + c];
  }
  double operator()(const So3GridIndex& i) const
  {
    return (*this)(i.beta, i.alpha, i.gamma);
  }

  /** \brief Grid sample with the largest C; ties go to the lowest flat index, for any
   *  \a num_threads. On a grid of limited tilt (So3Correlator::correlate with
   *  beta_rows) only the rows whose beta neighbors were computed take part, so the
   *  3 x 3 x 3 block around the result (rotationNeighborhood) is always sampled. */
  So3GridIndex argmax(int num_threads = 1) const;

  /** \brief Grid sample with the largest C among those within \a radius (radians,
   *  geodesic angle) of the identity, ties to the lowest flat index; the sample nearest
   *  the identity when none lies within \a radius. */
  So3GridIndex argmaxNearIdentity(double radius) const;

  /** \brief Beta rows computed: rows j < betaRows() hold C, the others -infinity
   *  (size() unless the correlation was limited in tilt). */
  int betaRows() const { return beta_rows_; }

private:
  friend class So3Correlator;
  int output_bandwidth_ = 0;
  int beta_rows_ = 0;
  std::size_t row_stride_ = 0; // 2 (Bo + 1): in-place c2r rows are padded
  double* data_ = nullptr;     // fftw_malloc'ed, beta_rows_ * N * row_stride_ doubles
};

/** \brief Beta rows of the (2Bo)^3 grid that hold every rotation of tilt (Euler beta,
 *  which is at most the rotation angle) up to \a max_tilt radians, plus one row so the
 *  neighborhood of each such sample is computed too; at most 2 Bo. */
int betaRowsForTilt(int output_bandwidth, double max_tilt);

/** \brief SO(3) correlation of two real spherical functions given by their spectra,
 *  Kostelec-Rockmore style: Wigner-d recurrence in l, then one 2-D c2r FFT per beta
 *  sample (doc/so3-correlation-spec.md section 3.4, the fast path for real inputs).
 *
 * Conventions: the target spectrum is conjugated, p_target = R p_source at the peak.
 * Output bandwidth Bo >= B samples the exact band-limited C on a finer grid.
 * Tables and FFTW plans are built once per (B, Bo); methods are const and thread-safe,
 * and results are bit-identical for any thread count.
 */
class So3Correlator {
public:
  /** \brief Shared instance for (B, Bo); Bo = 0 means Bo = B. Built on first use.
   *  \throws InvalidArgument unless 1 <= B <= Bo <= 256. */
  static std::shared_ptr<const So3Correlator> instance(int bandwidth,
                                                       int output_bandwidth = 0);

  So3Correlator(int bandwidth, int output_bandwidth = 0);
  ~So3Correlator();
  So3Correlator(const So3Correlator&) = delete;
  So3Correlator& operator=(const So3Correlator&) = delete;

  int bandwidth() const { return bandwidth_; }
  int outputBandwidth() const { return output_bandwidth_; }

  /** \brief C on the (2Bo)^3 grid.
   *  \param[in] target spectrum f (B x B), conjugated in the correlation
   *  \param[in] source spectrum h (B x B)
   *  \param[in] num_threads worker threads (>= 1)
   *  \param[in] beta_rows 0 (default): the whole grid; else only the rotations of tilt
   *  beta_j with j < beta_rows (any alpha and gamma), the rest of the grid is
   *  -infinity. A search near the identity (e.g. the residual of a re-projection pass)
   *  then costs about beta_rows / Bo of the whole grid; betaRowsForTilt gives the
   *  count for a tilt.
   *  \throws InvalidArgument when a spectrum is not B x B */
  So3CorrelationGrid correlate(const SphericalSpectrum& target,
                               const SphericalSpectrum& source, int num_threads = 1,
                               int beta_rows = 0) const;

private:
  int bandwidth_;
  int output_bandwidth_;
  std::vector<double> cos_beta_, log_cos_half_, log_sin_half_; // beta_j, j < Bo
  std::vector<double> log_factorials_;
  std::shared_ptr<const WignerStepTable> steps_;
  struct Plan;
  std::unique_ptr<Plan> plan_;
};

/** \brief Exact C(R) at arbitrary rotations (doc/so3-correlation-spec.md section 5),
 *  O(B^3) for the whole batch. Deterministic for any thread count. */
std::vector<double> evaluateCorrelation(const SphericalSpectrum& target,
                                        const SphericalSpectrum& source,
                                        const std::vector<Eigen::Matrix3d>& rotations,
                                        int num_threads = 1);

/** \brief A (target, source) spectrum pair for evaluateCorrelations (not owned). */
struct SpectrumPair {
  const SphericalSpectrum* target = nullptr;
  const SphericalSpectrum* source = nullptr;
};

/** \brief evaluateCorrelation for several spectrum pairs at the same rotations: the
 *  Wigner recurrence, the most expensive part, is run once and shared, so three pairs
 *  cost well under three single evaluations. Each pair's values equal those of
 *  evaluateCorrelation bit for bit. All spectra must have the same bandwidth.
 *  \return one vector of C values (one per rotation) per pair, in the order given
 *  \throws InvalidArgument on a null or mis-sized spectrum */
std::vector<std::vector<double>>
evaluateCorrelations(const std::vector<SpectrumPair>& pairs,
                     const std::vector<Eigen::Matrix3d>& rotations,
                     int num_threads = 1);

} // namespace pcl::phaser
