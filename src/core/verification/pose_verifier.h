/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "verification/pose_refinement.h"
#include "verification/ranking.h"

#include <Eigen/Core>

#include <vector>

namespace pcl::phaser {

/** \brief What verifies a pose q_t = R q_s + t both ways: the source's samples against
 *  the target's index and, seen from sensor origins, both free spaces. */
struct VerificationClouds {
  const PointIndex* target = nullptr; ///< target points at the verification radius
  const PointIndex* reach = nullptr;  ///< null, or the target at a larger radius
  const VerificationSamples* samples = nullptr; ///< the source's samples
  const VerificationSamples* polish = nullptr;  ///< samples thinned for refinement
  /** \brief Null about other centers (objects), else what the target's sensor saw. */
  const FreeSpace* target_free_space = nullptr;
  /** \brief Null when target_free_space is, else what the source's sensor saw (empty:
   *  the source is not seen from its center, no reverse test). */
  const FreeSpace* source_free_space = nullptr;
  const Eigen::Matrix3Xd* target_samples = nullptr; ///< for the reverse test
  const Eigen::VectorXd* target_weights = nullptr;  ///< one per target sample
};

/** \brief The ranked Verification (ranked) of \a pose: verifyPose of the source's
 *  samples and, with free spaces, the reverse violation of the target's samples in the
 *  source's frame. Deterministic for any \a num_threads. */
Verification verifyBothWays(const VerificationClouds& clouds, const RigidPose& pose,
                            int num_threads);

/** \brief refinePoseWithin of \a pose for \a iterations steps on the polish samples
 * (all samples when \a all_samples), within \a max_angle radians and \a max_shift
 * meters, with the reach index's first step; its look-ups on \a num_threads threads
 * (the same result for any count). */
RigidPose refineOnSamples(const VerificationClouds& clouds, const RigidPose& pose,
                          int iterations, double max_angle, double max_shift,
                          bool all_samples, int num_threads = 1);

/** \brief Standard error of the rank difference of poses \a a and \a b over the same
 *  samples (paired differences). Without free spaces the differences of closeness
 *  only, the samples of one cube of \a block meters counting as one; with them, also
 *  kViolationWeight x the violations both ways, each sample independent. */
double rankDifferenceError(const VerificationClouds& clouds, const RigidPose& a,
                           const RigidPose& b, double block, int num_threads);

} // namespace pcl::phaser
