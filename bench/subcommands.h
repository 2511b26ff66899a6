/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
/** \file subcommands.h
 * \brief The subcommands of pcl_phaser_bench (pcl_phaser_bench.cpp lists them), each
 * defined beside the work it runs.
 */
#pragma once

#include "bench_command_line.h"

namespace pcl::phaser {
namespace bench {

/** \brief compare: the methods on the shared scans under random poses (studies.cpp). */
extern const Subcommand kCompare;
/** \brief nees: getCovariance() against the errors (studies.cpp). */
extern const Subcommand kNees;
/** \brief detection: hasConverged() on right and wrong registrations (studies.cpp). */
extern const Subcommand kDetection;
/** \brief revisits: the real revisit pairs by distance (revisits.cpp). */
extern const Subcommand kRevisits;
/** \brief objects: the Stanford bunny's views (objects.cpp). */
extern const Subcommand kObjects;
/** \brief align: one align per stage (align_benchmark.cpp). */
extern const Subcommand kAlign;
/** \brief speed: aligns of the revisit pairs (revisit_speed.cpp). */
extern const Subcommand kSpeed;
/** \brief prior-map: relocalization in far site frames (prior_map_benchmark.cpp). */
extern const Subcommand kPriorMap;
/** \brief region: queries with a position prior (region_benchmark.cpp). */
extern const Subcommand kRegion;
/** \brief calibrate-covariance: the covariance model's inputs as CSV
 *  (covariance_calibration.cpp). */
extern const Subcommand kCalibrateCovariance;
/** \brief loop-closure: pcl_phaser_batch's records judged (loop_closure_report.cpp). */
extern const Subcommand kLoopClosure;
/** \brief yardstick: the time of one 128^3 FFT (fft_yardstick.cpp). */
extern const Subcommand kYardstick;

} // namespace bench
} // namespace pcl::phaser
