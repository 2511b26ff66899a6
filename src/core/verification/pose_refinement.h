/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "support/parallel.h"
#include "verification/verification.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace pcl::phaser {

/** \brief A rigid pose q_t = R q_s + t. */
struct RigidPose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

/** \brief Fewer samples than this are matched by the calling thread alone
 *  (forEachPlaneMatch): waking a worker costs more than the look-ups. */
constexpr Eigen::Index kMinParallelMatches = 1024;

/** \brief A sample the point-to-plane fit matched: its moved position q, the target
 *  point's normal n and residual n . (q - p), and the weight (sample weight) x
 *  (1 - |q - p|^2 / r^2)^2. */
struct PlaneMatch {
  Eigen::Vector3d position;
  Eigen::Matrix<double, 6, 1> jacobian; ///< [q x n; n]
  double weight;
  double residual;
};

/** \brief The plane match of sample \a i at \a pose into \a match (forEachPlaneMatch's
 *  test and fields); false when it has none. \a r2: the index radius squared. */
inline bool planeMatchAt(const PointIndex& target, const VerificationSamples& samples,
                         const RigidPose& pose, Eigen::Index i, double r2,
                         PlaneMatch& match)
{
  const bool with_normals = samples.normals.cols() == samples.points.cols();
  const Eigen::Vector3d q = pose.R * samples.points.col(i) + pose.t;
  const Eigen::Vector3d n_s = with_normals
                                  ? Eigen::Vector3d(pose.R * samples.normals.col(i))
                                  : Eigen::Vector3d::Zero();
  const Eigen::Index k = target.nearest(q, n_s, kMinNormalCosine);
  if (k < 0 || target.normal(k).isZero())
    return false;
  const Eigen::Vector3d n = target.normal(k);
  const Eigen::Vector3d d = q - target.point(k);
  const double closeness = 1.0 - d.squaredNorm() / r2;
  match.position = q;
  match.jacobian << q.cross(n), n;
  match.weight = samples.weights[i] * closeness * closeness;
  match.residual = n.dot(d);
  return true;
}

/** \brief Calls \a visit(PlaneMatch) for every sample, in sample order, whose moved
 *  position at \a pose has a nearest target point within the index radius (with an
 *  agreeing normal, kMinNormalCosine) that has a normal. With \a num_threads > 1 the
 *  look-ups run on up to that many threads (from kMinParallelMatches samples) and the
 *  calling thread visits the matches afterwards, still in sample order: what \a visit
 *  sums is the same for any thread count. */
template <typename Visit>
void forEachPlaneMatch(const PointIndex& target, const VerificationSamples& samples,
                       const RigidPose& pose, Visit&& visit, int num_threads = 1)
{
  const double r2 = target.radius() * target.radius();
  const Eigen::Index n = samples.points.cols();
  PlaneMatch match;
  if (num_threads <= 1 || n < kMinParallelMatches) {
    for (Eigen::Index i = 0; i < n; ++i)
      if (planeMatchAt(target, samples, pose, i, r2, match))
        visit(match);
    return;
  }
  std::vector<PlaneMatch> matches(static_cast<std::size_t>(n));
  std::vector<char> found(static_cast<std::size_t>(n), 0);
  detail::parallelFor(
      n, 256, num_threads, [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
        for (std::ptrdiff_t i = first; i < last; ++i)
          found[static_cast<std::size_t>(i)] = planeMatchAt(
              target, samples, pose, i, r2, matches[static_cast<std::size_t>(i)]);
      });
  for (std::size_t i = 0; i < matches.size(); ++i)
    if (found[i])
      visit(matches[i]);
}

/** \brief Local refinement of a pose that verifyPose scores: \a iterations
 *  Gauss-Newton steps on the point-to-plane distances of forEachPlaneMatch, whose
 *  weight derives from the closeness Verification::score averages. It climbs from
 *  a pose whose samples already partly touch the target; it does not search. Stops
 *  early once a step turns less than 1e-4 rad and moves less than 1 mm. Deterministic.
 *  \return the refined pose; \a start when fewer than six samples match */
RigidPose refinePose(const PointIndex& target, const VerificationSamples& samples,
                     const RigidPose& start, int iterations);

/** \brief refinePose within a trust region: the region's center as soon as a step turns
 *  the pose by more than \a max_angle (radians) or moves the sensor by more than
 *  \a max_shift (meters) from it (the climb left its basin).
 *  \param[in] reach null, or the same target indexed at a larger radius: one step
 *  against it first re-centers the climb and the trust region (skipped when it fails
 *  or leaves the region around \a start), so a start about that radius off still
 *  reaches the basin.
 *  \param[in] num_threads the look-ups' threads (forEachPlaneMatch): the same result
 *  for any count. */
RigidPose refinePoseWithin(const PointIndex& target, const VerificationSamples& samples,
                           const RigidPose& start, int iterations, double max_angle,
                           double max_shift, const PointIndex* reach = nullptr,
                           int num_threads = 1);

} // namespace pcl::phaser
