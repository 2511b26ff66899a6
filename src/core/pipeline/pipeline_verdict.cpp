/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The verdict on a pose: its rank, the limits, and whether it stands out from every
 * distinct hypothesis by more than the choice of samples explains.
 */
#include "pipeline/pipeline_verdict.h"

#include <map>

namespace pcl::phaser {
namespace detail {
namespace {

/** Fewest verification samples a source needs for its pose to be verified. */
constexpr int kMinVerificationSamples = 20;
/** Weight of a free-space violation (strong evidence) against an inlier (whose lack is
 *  weak: occlusion, partial overlap) in the rank. */
constexpr double kViolationWeight = 6.0;
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

/** Standard error of the weighted mean of \a d over \a points (3 x n), its samples
 *  grouped in cubes of \a block meters (0: each its own): sqrt(sum over cubes (sum w (d
 *  - mean))^2) / sum w. */
double meanError(const std::vector<double>& d, const Eigen::VectorXd& w,
                 const Eigen::Matrix3Xd& points, double block)
{
  double total = 0.0, mean = 0.0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    total += w[static_cast<Eigen::Index>(i)];
    mean += w[static_cast<Eigen::Index>(i)] * d[i];
  }
  if (!(total > 0.0))
    return 0.0;
  mean /= total;
  double sum = 0.0;
  if (!(block > 0.0)) {
    for (std::size_t i = 0; i < d.size(); ++i) {
      const double wi = w[static_cast<Eigen::Index>(i)];
      sum += wi * wi * (d[i] - mean) * (d[i] - mean);
    }
    return std::sqrt(sum) / total;
  }
  std::map<std::int64_t, double> cubes; // ordered: the same sum for any run
  for (std::size_t i = 0; i < d.size(); ++i) {
    std::int64_t key = static_cast<std::int64_t>(i) - (std::int64_t{1} << 62);
    voxelKey(points.col(static_cast<Eigen::Index>(i)), block, key);
    cubes[key] += w[static_cast<Eigen::Index>(i)] * (d[i] - mean);
  }
  for (const auto& cube : cubes)
    sum += cube.second * cube.second;
  return std::sqrt(sum) / total;
}

/** Standard error of the rank difference of \a a and \a b (paired sample differences).
 */
double rankDifferenceError(const SourceContext& source, const RigidPose& a,
                           const RigidPose& b)
{
  const int threads = source.params.num_threads;
  const TargetModel& target = source.target;
  const VerificationSamples& samples = source.samples;
  const std::vector<double> ca =
      sampleCloseness(target.index, samples, a.R, a.t, threads);
  const std::vector<double> cb =
      sampleCloseness(target.index, samples, b.R, b.t, threads);
  std::vector<double> d(ca.size());
  for (std::size_t i = 0; i < d.size(); ++i)
    d[i] = ca[i] - cb[i];
  // Evidence is correlated within a few coarse voxels (kFitBlockVoxels): without free
  // space, where chance matches of a compact object are refused by standing out alone,
  // the samples of one cube count as one. About viewpoints a violation outweighs six
  // inliers and the limits were set with independent samples (blocks there: 3 of the 36
  // revisits unclaimed, decisions.md).
  if (source.params.objects())
    return meanError(d, samples.weights, samples.points,
                     kFitBlockVoxels * target.coarse.grid.voxel_size);
  const std::vector<double> va =
      sampleViolations(target.free_space, samples.points, a.R, a.t, threads);
  const std::vector<double> vb =
      sampleViolations(target.free_space, samples.points, b.R, b.t, threads);
  for (std::size_t i = 0; i < d.size(); ++i)
    d[i] -= kViolationWeight * (va[i] - vb[i]);
  // Target samples in the source's frame: q_s = R^T (q_t - t).
  const auto reverseViolations = [&](const RigidPose& pose) {
    return sampleViolations(source.free_space, target.samples, pose.R.transpose(),
                            -(pose.R.transpose() * pose.t), threads);
  };
  const std::vector<double> ra = reverseViolations(a), rb = reverseViolations(b);
  std::vector<double> reverse(ra.size());
  for (std::size_t j = 0; j < reverse.size(); ++j)
    reverse[j] = -kViolationWeight * (ra[j] - rb[j]);
  const double source_error = meanError(d, samples.weights, samples.points, 0.0);
  const double target_error =
      meanError(reverse, target.sample_weights, target.samples, 0.0);
  return std::sqrt(source_error * source_error + target_error * target_error);
}

} // namespace

Verification ranked(const Verification& measured)
{
  Verification out = measured;
  out.rank =
      measured.score - kViolationWeight * (measured.free_space_violation +
                                           measured.reverse_free_space_violation);
  return out;
}

bool meetsLimits(const Verification& verification, const PhaserParameters& params)
{
  return verification.inlier_fraction >= params.min_inlier_fraction &&
         verification.constraint >= params.min_constraint &&
         std::max(verification.free_space_violation,
                  verification.reverse_free_space_violation) <=
             params.max_free_space_violation;
}

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
  if (source.params.verification)
    distinctness.error = rankDifferenceError(source, pose, {h.rotation, h.translation});
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
  if (!fitCovariance(source.target.index, source.samples, pose,
                     kFitBlockVoxels * source.target.coarse.grid.voxel_size,
                     result.fit_covariance))
    result.fit_covariance.setZero();
  diagnostics.times.verification += msSince(start);
  diagnostics.verified =
      diagnostics.verification_samples >= kMinVerificationSamples &&
      (!source.params.verification ||
       (pose.verifiable && meetsLimits(pose.verification, source.params) &&
        distinctness.stands_out));
}

} // namespace detail
} // namespace pcl::phaser
