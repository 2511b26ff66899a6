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
   *  (glibc only; elsewhere ignored): one malloc arena (M_ARENA_MAX 1), blocks up to
   *  32 MiB from the heap (M_MMAP_THRESHOLD), freed memory never returned
   *  (M_TRIM_THRESHOLD). Process-wide and permanent: the process keeps its peak memory
   *  (about 130 MB for a 120k-point pair at the defaults). Without them the first
   *  align of another thread still touches most of its memory anew, which is most of
   *  what a first align costs. */
  bool keep_memory = false;
};

/** \brief Does once what the first align() of a process would do first: builds the
 *  spherical harmonic transforms, SO(3) correlators, Wigner tables and FFTW plans of
 *  \a params, starts its worker threads and touches the memory of an align, by one
 *  align() of a built-in synthetic scan pair (a 64-ring scan of a hall seen from two
 *  poses) with one rotation and one orientation hypothesis: the same sizes, less work.
 *  Call it once, e.g. on a thread while the first clouds are read.
 *
 *  It changes no result: every later align() returns bit for bit what it would have
 *  returned without it; only the time of the first one changes. Thread-safe. Spatial
 *  FFT plans of grid dims other than the synthetic target's are built on first use.
 *  \param[in] params the parameters of the aligns that follow
 *  \param[in] options what to prepare for
 *  \return empty on success, else why the synthetic align failed (illegal parameters
 *  or options) */
std::string warmUp(const PhaserParameters& params, const WarmUpOptions& options = {});

} // namespace pcl::phaser
