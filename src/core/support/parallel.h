/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The engine's work sharing: a loop split into chunks, run by the calling thread and
 * the workers of a process-wide pool. A robot runs other programs: when the scheduler
 * parks a worker, OpenMP's barriers wait for it, and its waiting threads spin, taking
 * time from the threads that work; two threads were up to 1.7x slower than one on a
 * machine with a busy core (doc/benchmarks.md 11.18). Here the caller never waits for a
 * worker that holds no chunk, and a thread out of work polls for at most 50
 * microseconds before it blocks.
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

/** \brief Runs \a body over [0, count) in chunks of \a chunk indices (the last may be
 *  shorter), each on whichever of the calling thread and up to threads - 1 pool workers
 *  asks first. Returns when every chunk has ended; a worker that took none is not
 *  waited for. Runs on the calling thread alone when \a threads <= 1, when there is one
 *  chunk, or when no worker can be started. The chunks must be independent (write
 *  disjoint data), so results do not depend on which thread runs which. The first
 *  exception a chunk throws is rethrown after the others have ended (chunks not yet
 *  started then are skipped). Safe to call from several threads at once, and from
 *  inside a chunk (the inner call runs on the calling thread when the pool is busy). */
void parallelFor(std::ptrdiff_t count, std::ptrdiff_t chunk, int threads,
                 const ChunkBody& body);

} // namespace pcl::phaser::detail
