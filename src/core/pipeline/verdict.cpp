/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The verdict on a pose: the limits, and whether it stands out from every distinct
 * hypothesis by more than the choice of samples explains.
 */
#include "pipeline/stage_tasks.h"
#include "pipeline/verdict.h"
#include "uncertainty/pose_covariance.h"

namespace pcl::phaser::detail {
namespace {

/** Fewest verification samples a source needs for its pose to be verified. */
constexpr int kMinVerificationSamples = 20;
/** The final pose is distinct from the runner-up when its rank exceeds that one's by
 *  more than this many standard errors: the one-sided 99 % point of a normal. */
constexpr double kDistinctErrors = 2.33;

/** The best of \a hypotheses distinct from \a pose (angle, \a max_shift); -1: none. */
int runnerUp(const std::vector<Hypothesis>& hypotheses, const Pose& pose,
             double max_shift)
{
  int best = -1;
  for (std::size_t k = 0; k < hypotheses.size(); ++k) {
    const Hypothesis& h = hypotheses[k];
    const double angle = Eigen::AngleAxisd(pose.R.transpose() * h.rotation).angle();
    const bool distinct =
        angle > kHypothesisSeparation || (h.translation - pose.t).norm() > max_shift;
    if (distinct &&
        (best < 0 || h.verification.rank >
                         hypotheses[static_cast<std::size_t>(best)].verification.rank))
      best = static_cast<int>(k);
  }
  return best;
}

/** Edge of the cubes whose samples count as one without free space (kFitBlockVoxels
 *  coarse voxels): evidence is correlated within a few coarse voxels. */
double correlatedBlock(const SourceContext& source)
{
  return kFitBlockVoxels * source.target.coarse.grid.voxel_size;
}

} // namespace

Distinctness standsOut(const SourceContext& source, const Pose& pose,
                       const std::vector<Hypothesis>& hypotheses)
{
  Distinctness distinctness;
  // Distinct poses are those a local refinement (two coarse voxels) cannot join.
  const int k = runnerUp(hypotheses, pose, 2.0 * source.target.coarse.grid.voxel_size);
  if (k < 0)
    return distinctness;
  const Hypothesis& h = hypotheses[static_cast<std::size_t>(k)];
  distinctness.runner_up_rank = h.verification.rank;
  if (source.verification)
    distinctness.error = rankDifferenceError(
        source.verificationClouds(), pose, {h.rotation, h.translation},
        correlatedBlock(source), source.settings.params.num_threads);
  distinctness.stands_out = pose.verification.rank - distinctness.runner_up_rank >
                            kDistinctErrors * distinctness.error;
  return distinctness;
}

void judgeFinalPose(const SourceContext& source, const Pose& pose, PhaserResult& result)
{
  PhaserDiagnostics& diagnostics = result.diagnostics;
  diagnostics.verification = pose.verification;
  diagnostics.verification_samples = static_cast<int>(source.samples.points.cols());
  const auto start = Clock::now();
  const Distinctness distinctness = standsOut(source, pose, diagnostics.hypotheses);
  diagnostics.runner_up_rank = distinctness.runner_up_rank;
  diagnostics.runner_up_error = distinctness.error;
  if (!fitCovariance(source.target.index, source.samples, pose, correlatedBlock(source),
                     result.fit_covariance, source.settings.params.num_threads))
    result.fit_covariance.setZero();
  diagnostics.times.verification += msSince(start);
  diagnostics.verified =
      diagnostics.verification_samples >= kMinVerificationSamples &&
      (!source.verification ||
       (pose.verifiable && meetsLimits(pose.verification, source.settings.limits) &&
        distinctness.stands_out));
}

} // namespace pcl::phaser::detail
