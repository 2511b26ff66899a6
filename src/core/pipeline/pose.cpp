/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "pipeline/pose.h"
#include "pipeline/stage_tasks.h"

namespace pcl::phaser::detail {
namespace {

/** Gauss-Newton steps of the local refinement on the verification samples. */
constexpr int kLocalRefinementSteps = 10;

} // namespace

bool improves(const Pose& next, const Pose& current)
{
  return !current.verifiable || next.verification.rank > current.verification.rank;
}

Verification verificationOf(const SourceContext& source, const RigidPose& pose,
                            StageTimes& times, int num_threads)
{
  const auto start = Clock::now();
  const Verification verification =
      verifyBothWays(source.verificationClouds(), pose, num_threads);
  times.verification += msSince(start);
  return verification;
}

Pose refinedOnSamples(const SourceContext& source, const Pose& pose, StageTimes& times,
                      int num_threads, bool all_samples)
{
  const auto start = Clock::now();
  const RigidPose refined = refineOnSamples(
      source.verificationClouds(), pose, kLocalRefinementSteps, kHypothesisSeparation,
      2.0 * source.target.coarse.grid.voxel_size, all_samples, num_threads);
  times.verification += msSince(start);
  if (refined.R == pose.R && refined.t == pose.t)
    return pose; // refused or nothing to climb: verifies the same
  Pose next = pose;
  static_cast<RigidPose&>(next) = refined;
  next.verification = verificationOf(source, next, times, num_threads);
  return next.verification.rank > pose.verification.rank ? next : pose;
}

} // namespace pcl::phaser::detail
