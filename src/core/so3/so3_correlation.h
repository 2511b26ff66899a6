/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "so3/so3_correlation_grid.h"
#include "so3/wigner.h"
#include "sphere/spherical_harmonics.h"

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <vector>

namespace pcl::phaser {

/** \brief SO(3) correlation of two real spherical functions from their spectra
 *  (Kostelec-Rockmore): Wigner-d recurrence in l, then one 2-D c2r FFT per beta
 *  sample. The target spectrum is conjugated, so p_target = R p_source at the peak; an
 *  output bandwidth Bo >= B samples the band-limited C on a finer grid. Tables and
 * plans are built once per (B, Bo); thread-safe, bit-identical for any thread count. */
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

  /** \brief C on the (2Bo)^3 grid of the \a target and \a source spectra (B x B).
   *  \param[in] beta_rows 0: the whole grid; else only the rows beta_j with j <
   *  beta_rows (betaRowsForTilt), the rest -infinity, at about beta_rows / Bo the cost
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

/** \brief A (target, source) spectrum pair for evaluateCorrelations (not owned). */
struct SpectrumPair {
  const SphericalSpectrum* target = nullptr;
  const SphericalSpectrum* source = nullptr;
};

/** \brief Exact C(R) of every spectrum pair at arbitrary rotations, O(B^3) for the
 *  whole batch: the Wigner recurrence, the most expensive part, is run once and shared
 *  by the pairs; each pair's values are those it would get alone, bit for bit. All
 *  spectra must have the same bandwidth. Deterministic for any thread count.
 *  \return one vector of C values (one per rotation) per pair, in the order given
 *  \throws InvalidArgument on a null or mis-sized spectrum */
std::vector<std::vector<double>>
evaluateCorrelations(const std::vector<SpectrumPair>& pairs,
                     const std::vector<Eigen::Matrix3d>& rotations,
                     int num_threads = 1);

} // namespace pcl::phaser
