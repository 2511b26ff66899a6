/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "so3/so3_correlation_grid.h"
#include "so3/so3_grid.h"
#include "so3/wigner.h"
#include "sphere/spherical_harmonics.h"

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <vector>

namespace pcl::phaser {

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
