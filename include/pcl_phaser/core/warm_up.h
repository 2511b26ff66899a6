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
  /** \brief Channels fused beside the geometry in the aligns that follow (intensity:
   *  1), 0..8. */
  std::size_t channels = 1;
  /** \brief Points of each synthetic scan, 1000..2000000: about those of the clouds
   *  that follow (the memory an align touches grows with them). */
  int points = 120000;
  /** \brief Also make the process keep the memory of an align for the next one
   *  (glibc only; elsewhere ignored): one malloc arena for all threads
   *  (M_ARENA_MAX 1, so that memory touched by the warm-up thread serves the thread
   *  that aligns), blocks up to 32 MiB from the heap rather than fresh mappings
   *  (M_MMAP_THRESHOLD) and freed memory never returned to the system
   *  (M_TRIM_THRESHOLD). These settings are process-wide and stay: the process keeps
   *  its peak memory (about 130 MB for a 120k-point pair at the defaults, the peak of
   *  one align without them too). Without them the first align of another thread
   *  still touches most of its memory anew, which is most of what the first align
   *  costs (doc/benchmarks.md 11.22). */
  bool keep_memory = false;
};

/** \brief Does once what the first align() of a process would do first: builds the
 *  process-wide spherical harmonic transforms, SO(3) correlators, Wigner tables and
 *  FFTW plans of \a params, starts the worker threads of \a params.num_threads, and
 *  makes the process touch the memory of an align, by one align() of a built-in
 *  synthetic scan pair (a 64-ring scan of a hall, \a options.points points, seen from
 *  two poses) with one rotation and one orientation hypothesis: the same sizes, hence
 *  the same tables, plans and buffers, for less work. Call it once, e.g. on a thread
 *  while the first clouds are read; it costs less than a first align of clouds of
 *  that size (doc/benchmarks.md 11.22).
 *
 *  Contract: it changes no result. Every later align() returns bit for bit what it
 *  would have returned without it (the cached objects are immutable and depend on the
 *  sizes only); only the time of the first align() changes. Thread-safe: it may run
 *  concurrently with align() and with itself. Spatial FFT plans depend on the grid
 *  dims of each target: plans of other dims are still built on their first use.
 *  \param[in] params the parameters of the aligns that follow
 *  \param[in] options what to prepare for
 *  \return empty on success, else why the synthetic align failed (illegal parameters
 *  or options) */
std::string warmUp(const PhaserParameters& params, const WarmUpOptions& options = {});

} // namespace pcl::phaser
