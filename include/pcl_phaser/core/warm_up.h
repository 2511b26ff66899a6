/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/core/pipeline.h>

#include <cstddef>
#include <string>

namespace pcl::phaser {

/** \brief What warmUp() prepares for. */
struct WarmUpOptions {
  std::size_t channels = 1; ///< fused in the aligns to come, 0..8
  int points = 120000;      ///< per synthetic scan, 1000..2000000: as the next clouds
  /** \brief Also make the process keep the memory of an align for the next one
   *  (glibc only: one malloc arena, blocks up to 32 MiB from the heap, no trimming).
   *  Process-wide and permanent: the process keeps its peak memory (about 130 MB for a
   *  120k-point pair at the defaults). */
  bool keep_memory = false;
};

/** \brief Does once what the first align() of a process would do first (transforms,
 *  FFTW plans, worker threads, memory) by aligning a built-in synthetic scan pair.
 *  Call it once, e.g. on a thread while the first clouds are read. Thread-safe; every
 *  later align() returns bit for bit what it would have without it.
 *  \param[in] params the parameters of the aligns that follow
 *  \param[in] options what to prepare for
 *  \return empty on success, else why the synthetic align failed (illegal parameters
 *  or options) */
std::string warmUp(const PhaserParameters& params, const WarmUpOptions& options = {});

} // namespace pcl::phaser
