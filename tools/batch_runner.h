// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file batch_runner.h
 * \brief The run of `pcl_phaser_batch`: the pairs of one shard aligned in an order that
 * prepares each target once, a cache of loaded clouds and prepared targets, records
 * appended as pairs finish, resume, progress, and a clean stop on SIGINT / SIGTERM.
 */
#pragma once

#include "batch_pairs.h"
#include "batch_records.h"

#include <pcl_phaser/core/pipeline.h>

#include <optional>
#include <string>

namespace pcl {
namespace phaser {
namespace batch {

/** \brief Exit codes of pcl_phaser_batch. */
enum ExitCode {
  kOk = 0,           ///< every pair of the shard is recorded (failed pairs included)
  kUsage = 1,        ///< bad command line or option value
  kInput = 2,        ///< an input list (pairs, scans, poses, parts) is unreadable
  kOutput = 3,       ///< --out or --g2o cannot be written
  kInterrupted = 130 ///< SIGINT / SIGTERM: the pairs in flight finished, rerun resumes
};

/** \brief What one run does. */
struct RunSettings {
  std::string out;           ///< the JSONL file (appended to; resumed from)
  std::string g2o;           ///< the g2o graph to write at the end; empty: none
  int shard = 0, shards = 1; ///< this part, of how many
  /** \brief Prepared targets each job keeps, least recently used out first, >= 1. A
   *  prepared target holds its spectra (tens of MB at the defaults); pairs come
   *  grouped by target, so 1 already prepares each target once per job. */
  int cache = 4;
  /** \brief Pairs aligned at once, >= 1, each job taking whole target groups. With
   *  more than one and PhaserParameters::num_threads 0, the hardware threads are
   *  split between the jobs. */
  int jobs = 1;
  PhaserParameters params; ///< the registration settings
  /** \brief With poses: odometry edges and `FIX 0` in the g2o graph; empty: none. */
  std::optional<OdometrySigma> odometry;
};

/** \brief Align the pairs of shard RunSettings::shard of \a list, skipping those
 *  already recorded in RunSettings::out, appending a record per pair as it finishes,
 *  then write the g2o graph of every record in the file.
 *  \return an ExitCode */
int runBatch(const PairList& list, const RunSettings& settings);

} // namespace batch
} // namespace phaser
} // namespace pcl
