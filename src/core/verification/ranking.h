/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/core/result.h>

namespace pcl::phaser {

/** \brief Weight of a free-space violation (strong evidence) against an inlier (whose
 *  lack is weak: occlusion, partial overlap) in Verification::rank. */
constexpr double kViolationWeight = 6.0;

/** \brief \a measured with its rank: score less kViolationWeight x both violations. */
Verification ranked(const Verification& measured);

/** \brief The limits a verified pose meets, set from the PhaserParameters of the same
 *  names; the defaults limit nothing. */
struct VerificationLimits {
  double min_inlier_fraction = 0.0;      ///< weighted share of the samples, [0, 1]
  double min_constraint = 0.0;           ///< Verification::constraint, [0, 1]
  double max_free_space_violation = 1.0; ///< weighted share of the samples, [0, 1]
};

/** \brief Whether \a verification meets \a limits: enough inliers and constraint, and
 *  neither free-space violation above its limit. */
bool meetsLimits(const Verification& verification, const VerificationLimits& limits);

} // namespace pcl::phaser
