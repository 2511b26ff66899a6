/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The one trial-and-report path of pcl_phaser_bench compare, nees, detection, revisits
 * and objects: the options they share, what they record per registration (Judged,
 * methods.h), the summaries of groups of trials, the markdown tables, the CSV and the
 * gnuplot plots.
 */
#pragma once

#include "bench_command_line.h"
#include "methods.h"

#include <cmath>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

namespace pcl::phaser {
namespace bench {

/** \brief One registration of one method on one pair of compare, nees or detection. */
struct Trial : Judged {
  std::string set;    ///< what was registered: a scan name, a pair, "unrelated", ...
  std::string sweep;  ///< clean, noise, sparsity, overlap
  double value = 0.0; ///< the sweep's parameter (PSNR dB or kept fraction)
  int pose = 0;       ///< index of the random pose (0 for real pairs)
  int bandwidth = 0;  ///< pcl_phaser's bandwidth (0 for other methods)
};

/** \brief The options the studies share (--data, --methods, --seed, --fpcs-time,
 *  --voxel, --csv, --md, --plots and the engine's); a study without one keeps its
 *  default. */
struct StudyOptions {
  std::string data;
  std::vector<std::string> methods;
  int fpcs_seconds = 10;
  unsigned seed = 1;
  double voxel = 0.0;      ///< leaf of PCL's methods
  PhaserParameters engine; ///< pcl_phaser's settings; its threads every method's
  std::string csv, markdown, plots;
};

/** \brief Reads the shared options of \a args into \a o, --methods defaulting to
 *  \a methods and --voxel to \a voxel (the engine with 2 threads); malformed values are
 *  recorded in \a args. */
void readStudyOptions(BenchArguments& args, StudyOptions& o,
                      std::vector<std::string> methods, double voxel);

/** \brief Records in \a args the first problem of \a o's shared options: a method
 *  unknown (or, when \a require_methods, none given), --threads or --fpcs-time < 1. */
void checkStudyOptions(BenchArguments& args, const StudyOptions& o,
                       bool require_methods);

/** \brief Counts and medians of a group of trials. */
struct Summary {
  int n = 0, ok = 0;                          ///< trials, successes
  int converged_ok = 0, converged_failed = 0; ///< converged successes, failures
  double median_rre = NAN, median_rte = NAN;  ///< over the successes
  double median_ms = NAN, p90_ms = NAN;       ///< over all the trials
};

/** \brief The Summary of \a group. */
Summary summarize(const std::vector<const Judged*>& group);

/** \brief The trials of \a trials that \a take, as pointers (for summarize()). */
template <class T, class Take>
std::vector<const Judged*> select(const std::vector<T>& trials, Take take)
{
  std::vector<const Judged*> out;
  for (const T& t : trials)
    if (take(t))
      out.push_back(&t);
  return out;
}

/** \brief How the covariance of a group's converged trials with one (NEES >= 0) covers
 *  their errors: how many, mean and median 6-D NEES, inside the 95 % ellipsoids (6-D,
 *  and each block in 3-D), mean NEES per block, RMS errors, median sigmas (NaN for
 *  none). */
struct NeesSummary {
  int n = 0, inside = 0, inside_rot = 0, inside_trans = 0;
  double mean = NAN, median = NAN, mean_rot = NAN, mean_trans = NAN;
  double rms_rre = NAN, rms_rte = NAN, sigma_rot = NAN, sigma_trans = NAN;
};

/** \brief The NeesSummary of \a group. */
NeesSummary summarizeNees(const std::vector<const Judged*>& group);

/** \brief Writes every trial as a CSV row (with a header): the trial, `fitness_score`
 *  (PCL's getFitnessScore; empty for pcl_phaser), the NEES, then pcl_phaser's result
 *  fields (result_csv.h). */
void writeCsv(std::ostream& out, const std::vector<Trial>& trials);

/** \brief Markdown table of where each method's time goes: for each of \a methods with
 *  trials in \a group, in that order, a row "total" (the median time per trial) and one
 *  per stage (Judged::stages, in the order of the method's first trial; median over
 *  the trials), each in ms, in FFT128 (\a fft_ms) and as a share of the first method's
 *  median total. Medians of stages need not add up to the median total. */
void writeStageTable(std::ostream& out, const std::vector<const Judged*>& group,
                     const std::vector<std::string>& methods, double fft_ms);

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

/** \brief Writes \a base.gp: a pngcairo terminal of \a size ("W,H") writing base.png,
 *  then \a script; runs it when gnuplot is installed. \return base.png, or "" when
 *  gnuplot is missing or failed */
std::string plotPng(const std::string& base, const char* size,
                    const std::string& script);

/** \brief The markdown stream of a study: \a file opened on \a path, or stdout when
 *  \a path is empty; "Command: `command`" and a blank line written to it. */
std::ostream& openMarkdown(const std::string& path, std::ofstream& file,
                           const std::string& command);

/** \brief The paragraph of the yardstick: one 128^3 FFT took \a fft_ms ms (FFT128). */
std::string yardstickLine(double fft_ms);

/** \brief A markdown table's header: "| A | B |" and "|---|---|", lines ended. */
std::string tableHeader(const std::vector<std::string>& columns);

/** \brief \a value printed with the printf format \a fmt, or "-" when not finite. */
std::string formatValue(const char* fmt, double value);

} // namespace bench
} // namespace pcl::phaser
