/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: the stages' clock and their one-thread tasks.
#include "support/parallel.h"

#include <algorithm>
#include <chrono>

namespace pcl::phaser::detail {

using Clock = std::chrono::steady_clock;

/** Milliseconds since \a start. */
inline double msSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/** \a task(k) for k = 0 .. count - 1 as independent one-thread tasks on at most
 *  \a num_threads threads; the first exception is rethrown when the others have ended.
 */
template <typename Task>
void runTasks(int count, int num_threads, const Task& task)
{
  parallelFor(count, 1, std::min(num_threads, count),
              [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
                for (std::ptrdiff_t k = first; k < last; ++k)
                  task(static_cast<int>(k));
              });
}

} // namespace pcl::phaser::detail
