/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

namespace pcl::phaser {
namespace bench {

/** \brief The timing yardstick of doc/benchmarks.md: milliseconds of one 128^3
 *  real-to-complex FFTW transform on one thread (FFTW_MEASURE plan, median of 15
 *  executions). These VMs differ up to threefold in speed, so timings are reported in
 *  these units too. Call it before any registration: it forgets FFTW's wisdom after
 *  itself, so the library's own plans are those of a run without it. */
double fftYardstickMs();

} // namespace bench
} // namespace pcl::phaser
