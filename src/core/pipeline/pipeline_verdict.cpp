/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The verdict on a pose about sensor origins: how verified poses rank, the limits a
 * right pose meets, and whether the final pose stands out from every distinct
 * hypothesis by more than the choice of samples explains.
 */
#include "pipeline/pipeline_internal.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace pcl::phaser {
namespace detail {

/** How a verified pose ranks: its closeness-weighted inlier share less a multiple of
 *  its free-space violations, of the source's samples in space the target saw through
 *  and of the target's samples in space the source saw through. A violation is strong
 *  evidence against the pose and each sensor's is separate evidence; a sample without
 *  a target neighbor is weak (occlusion, partial overlap), hence the factor. */
double rank(const PoseVerification& v)
{
  return v.score -
         kViolationWeight * (v.free_space_violation + v.reverse_free_space_violation);
}

/** Whether \a v meets the verification limits of \a p (inliers, constraint and both
 *  free-space violations): a pose that could be declared right. */
bool meetsLimits(const PoseVerification& v, const PhaserParameters& p)
{
  return v.inlier_fraction >= p.min_inlier_fraction &&
         v.constraint >= p.min_constraint &&
         std::max(v.free_space_violation, v.reverse_free_space_violation) <=
             p.max_free_space_violation;
}

namespace {

/** The hypothesis of highest verification rank among \a hypotheses distinct from
 *  \a pose: turned from it by more than the hypothesis separation, or moved by more
 *  than \a max_shift meters (centered coordinates); -1 when there is none. */
int runnerUp(const std::vector<RotationHypothesis>& hypotheses, const Pose& pose,
             double max_shift)
{
  int best = -1;
  for (std::size_t k = 0; k < hypotheses.size(); ++k) {
    const RotationHypothesis& h = hypotheses[k];
    const double angle = Eigen::AngleAxisd(pose.R.transpose() * h.rotation).angle();
    const bool distinct =
        angle > kHypothesisSeparation || (h.translation - pose.t).norm() > max_shift;
    if (distinct &&
        (best < 0 || h.verification_rank >
                         hypotheses[static_cast<std::size_t>(best)].verification_rank))
      best = static_cast<int>(k);
  }
  return best;
}

/** Standard error of the weighted mean of \a d (weights \a w): sqrt(sum w^2 (d -
 *  mean)^2) / sum w. */
double meanError(const std::vector<double>& d, const Eigen::VectorXd& w)
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
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double wi = w[static_cast<Eigen::Index>(i)];
    sum += wi * wi * (d[i] - mean) * (d[i] - mean);
  }
  return std::sqrt(sum) / total;
}

/** Standard error of rank(a.v) - rank(b.v) from the samples' paired differences: the
 *  same source samples (closeness less kViolationWeight x violation) and the same
 *  target samples (reverse violations) under both poses (about sensor origins). A
 *  difference within a few of it is what the choice of samples alone could give. */
double rankDifferenceError(const SourceContext& s, const Pose& a, const Pose& b)
{
  const int threads = s.p.num_threads;
  const std::vector<double> ca =
      sampleCloseness(s.target.index, s.samples, a.R, a.t, threads);
  const std::vector<double> cb =
      sampleCloseness(s.target.index, s.samples, b.R, b.t, threads);
  std::vector<double> d(ca.size());
  for (std::size_t i = 0; i < d.size(); ++i)
    d[i] = ca[i] - cb[i];
  const FreeSpace& target_seen = s.target.free_space;
  const std::vector<double> va =
      sampleViolations(target_seen, s.samples.points, a.R, a.t, threads);
  const std::vector<double> vb =
      sampleViolations(target_seen, s.samples.points, b.R, b.t, threads);
  for (std::size_t i = 0; i < d.size(); ++i)
    d[i] -= kViolationWeight * (va[i] - vb[i]);
  // Target samples in the source's frame: q_s = R^T (q_t - t).
  const Eigen::Matrix3Xd& ts = s.target.samples;
  const std::vector<double> ra = sampleViolations(s.free_space, ts, a.R.transpose(),
                                                  -(a.R.transpose() * a.t), threads);
  const std::vector<double> rb = sampleViolations(s.free_space, ts, b.R.transpose(),
                                                  -(b.R.transpose() * b.t), threads);
  std::vector<double> e(ra.size());
  for (std::size_t j = 0; j < e.size(); ++j)
    e[j] = -kViolationWeight * (ra[j] - rb[j]);
  const double source = meanError(d, s.samples.weights);
  const double target = meanError(e, s.target.sample_weights);
  return std::sqrt(source * source + target * target);
}

} // namespace

Distinctness standsOut(const SourceContext& s, const Pose& pose,
                       const std::vector<RotationHypothesis>& hypotheses)
{
  Distinctness d;
  // Distinct poses are those a polish (two coarse voxels) cannot join.
  const int k = runnerUp(hypotheses, pose, 2.0 * s.target.coarse.grid.voxel_size);
  if (k < 0)
    return d;
  const RotationHypothesis& h = hypotheses[static_cast<std::size_t>(k)];
  d.runner_up_rank = h.verification_rank;
  if (s.p.sensor_centered) {
    Pose other;
    other.R = h.rotation;
    other.t = h.translation;
    d.error = rankDifferenceError(s, pose, other);
  }
  d.stands_out = rank(pose.v) - d.runner_up_rank > kDistinctErrors * d.error;
  return d;
}

/** The covariance of the final \a pose from its own point-to-plane fit into \a e
 *  (fitCovariance over blocks of kFitBlockVoxels coarse voxels; zero when the fit
 *  cannot give one), about the target's projection center. */
void fitUncertainty(const SourceContext& s, const Pose& pose, PhaserEstimate& e)
{
  if (!fitCovariance(s.target.index, s.samples, {pose.R, pose.t},
                     kFitBlockVoxels * s.target.coarse.grid.voxel_size,
                     e.fit_covariance))
    e.fit_covariance.setZero();
}

/** The final \a pose and its verification figures into \a e, and the verdict. */
void verdict(const SourceContext& s, const Pose& pose, PhaserEstimate& e)
{
  e.rotation = pose.R;
  e.translation = pose.t;
  e.inlier_fraction = pose.v.inlier_fraction;
  e.free_space_violation = pose.v.free_space_violation;
  e.reverse_free_space_violation = pose.v.reverse_free_space_violation;
  e.constraint = pose.v.constraint;
  e.verification_samples = static_cast<int>(s.samples.points.cols());
  e.verification_score = pose.v.score;
  e.verification_rank = rank(pose.v);
  const auto start = Clock::now();
  const Distinctness d = standsOut(s, pose, e.hypotheses);
  e.runner_up_rank = d.runner_up_rank;
  e.runner_up_error = d.error;
  fitUncertainty(s, pose, e);
  e.verification_ms += msSince(start);
  e.verified = e.verification_samples >= kMinVerificationSamples &&
               (!s.p.sensor_centered ||
                (pose.verifiable && meetsLimits(pose.v, s.p) && d.stands_out));
}

} // namespace detail
} // namespace pcl::phaser
