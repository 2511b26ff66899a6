/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * What the timing programs measure of one align: wall time, minor page faults and the
 * engine's stages; and the median they report.
 */
#pragma once

#include <pcl_phaser/phaser_registration.h>

#include <algorithm>
#include <chrono>
#include <sys/resource.h>
#include <vector>

namespace pcl::phaser::bench {

using Clock = std::chrono::steady_clock;

/** \brief Milliseconds since \a start. */
inline double msSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/** \brief Minor page faults of the process so far. */
inline long minorFaults()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

/** \brief One align: wall time, minor page faults, the engine's stages. */
struct Timing {
  double ms = 0.0;
  long faults = 0;
  StageTimes stages;
};

/** \brief \a phaser.align() timed. */
template <typename PointT>
Timing timedAlign(pcl::PhaserRegistration<PointT, PointT>& phaser)
{
  pcl::PointCloud<PointT> out;
  const long faults = minorFaults();
  const auto start = Clock::now();
  phaser.align(out);
  return {msSince(start), minorFaults() - faults, phaser.getResult().diagnostics.times};
}

} // namespace pcl::phaser::bench
