/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * What pcl_phaser_bench compare, nees and detection record per registration, and its
 * summaries: the markdown tables, the CSV, and gnuplot plots of the sweeps.
 */
#pragma once

#include "methods.h"

#include <ostream>
#include <string>
#include <vector>

namespace pcl::phaser {
namespace bench {

/** \brief One registration of one method on one pair. */
struct Trial {
  std::string set;    ///< what was registered: a scan name, a pair, "unrelated", ...
  std::string sweep;  ///< clean, noise, sparsity, overlap
  double value = 0.0; ///< the sweep's parameter (PSNR dB or kept fraction)
  int pose = 0;       ///< index of the random pose (0 for real pairs)
  std::string method; ///< e.g. "phaser", "sacia+icp"
  int bandwidth = 0;  ///< pcl_phaser's bandwidth (0 for other methods)
  double rre_deg = 0.0, rte_m = 0.0, ms = 0.0;
  bool converged = false;   ///< the method's own verdict
  bool success = false;     ///< RRE and RTE under the thresholds
  double score = 0.0;       ///< the method's quality figure (see MethodResult)
  double nees = -1.0;       ///< 6-D NEES under the method's covariance, -1 without one
  double nees_rot = -1.0;   ///< 3-D NEES of the rotation error under its own block
  double nees_trans = -1.0; ///< 3-D NEES of the translation error under its own block
  double sigma_rot_deg = 0.0; ///< sqrt(trace) of the covariance's rotation block
  double sigma_trans_m = 0.0; ///< sqrt(trace) of its translation block
  std::optional<PhaserResult> phaser; ///< pcl_phaser's result (MethodResult)
};

/** \brief Writes every trial as a CSV row (with a header): the trial, `fitness_score`
 *  (PCL's getFitnessScore; empty for pcl_phaser), the NEES, then pcl_phaser's result
 *  fields (result_csv.h). */
void writeCsv(std::ostream& out, const std::vector<Trial>& trials);

/** \brief Markdown table grouped by (sweep, value, method) over all sets, or by (set,
 * method) when \a by_set: trials, success rate, median RRE / RTE over successes, median
 * and p90 time. */
void writeSummary(std::ostream& out, const std::vector<Trial>& trials, bool by_set);

/** \brief NEES summary per bandwidth: converged trials, mean NEES (6 if consistent),
 * fraction inside the 95 % ellipsoid, RMS errors and the covariance's own spread. */
void writeNeesSummary(std::ostream& out, const std::vector<Trial>& trials);

/** \brief Precision and recall of "converged" as a detector of success, and for
 * thresholds on the score (larger is better), per method. */
void writeDetectionSummary(std::ostream& out, const std::vector<Trial>& trials,
                           const std::vector<double>& thresholds);

/** \brief For each sweep present (noise, sparsity, overlap): a .dat and a .gp in \a dir
 * and, when gnuplot is installed, a PNG of success rate and median RRE against the
 * sweep's parameter, one line per method. Returns the PNGs written. */
std::vector<std::string> writePlots(const std::string& dir,
                                    const std::vector<Trial>& trials);

/** \brief \a value printed with the printf format \a fmt, or "-" when not finite. */
std::string formatValue(const char* fmt, double value);

} // namespace bench
} // namespace pcl::phaser
