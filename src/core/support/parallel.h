/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The engine's work sharing: a loop split into chunks, run by the calling thread and
 * the workers of a process-wide pool. The caller never waits for a worker that holds
 * no chunk (OpenMP's barriers wait for parked workers: two threads measured up to 1.7x
 * slower than one beside a busy core).
 */
#pragma once

#include <cstddef>
#include <functional>

namespace pcl::phaser::detail {

/** \brief What a chunk runs: body(first, last, slot) for the indices [first, last);
 *  \a slot, in [0, threads), is unique among the threads taking part in one call
 *  (the caller is 0), e.g. to index per-thread scratch. */
using ChunkBody =
    std::function<void(std::ptrdiff_t first, std::ptrdiff_t last, int slot)>;

/** \brief Runs \a body over [0, count) in chunks of \a chunk indices, each on whichever
 *  of the calling thread and up to threads - 1 pool workers asks first; returns when
 *  every chunk has ended. Chunks must write disjoint data. The first exception a chunk
 *  throws is rethrown after the others ended (chunks not yet started are skipped).
 *  Safe from several threads at once and from inside a chunk. */
void parallelFor(std::ptrdiff_t count, std::ptrdiff_t chunk, int threads,
                 const ChunkBody& body);

} // namespace pcl::phaser::detail
