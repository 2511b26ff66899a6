// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file batch_progress.h
 * \brief The progress line of `pcl_phaser_batch` on stderr: pairs done / total, pairs
 * per second, time left, accepted so far; redrawn in place on a terminal, one plain
 * line per pair otherwise (logs of GNU parallel and Slurm).
 */
#pragma once

#include "batch_pairs.h"
#include "batch_records.h"

#include <chrono>
#include <cstddef>
#include <vector>

namespace pcl {
namespace phaser {
namespace batch {

/** \brief Records that converged. */
std::size_t countAccepted(const std::vector<Record>& records);

/** \brief Counts pairs as they finish and reports on stderr. */
class Progress {
public:
  /** \param[in] total pairs of the shard \param[in] done already recorded (resumed)
   *  \param[in] accepted of those, converged */
  Progress(std::size_t total, std::size_t done, std::size_t accepted);
  /** \brief One more pair finished with \a record. */
  void finished(const Pair& pair, const Record& record);
  /** \brief End the line drawn in place, then a summary of this run's pairs: wall
   *  time and minor page faults (fresh memory pages the process touched) a pair. */
  void close();
  /** \brief Pairs recorded, resumed ones included. */
  std::size_t done() const { return done_; }

private:
  std::size_t total_, done_, accepted_, failed_ = 0, resumed_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_;
  long start_faults_ = 0; ///< minor page faults of the process at the start
};

} // namespace batch
} // namespace phaser
} // namespace pcl
