/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "verification/pose_refinement.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace pcl::phaser {

namespace {

/** The steps stop once one turns less than this (radians, 0.006 deg)... */
constexpr double kMinStepAngle = 1e-4;
/** ... and moves less than this (meters). */
constexpr double kMinStepShift = 1e-3;

/** exp of the skew matrix of \a w (Rodrigues). */
Eigen::Matrix3d expSo3(const Eigen::Vector3d& w)
{
  const double angle = w.norm();
  if (angle < 1e-12)
    return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

/** One Gauss-Newton sweep at \a pose: the normal equations (H, g) of the samples'
 *  weighted point-to-plane distances. Returns the number of matches. */
int sweep(const PointIndex& target, const VerificationSamples& samples,
          const RigidPose& pose, Eigen::Matrix<double, 6, 6>& H,
          Eigen::Matrix<double, 6, 1>& g, int num_threads)
{
  H.setZero();
  g.setZero();
  int matched = 0;
  forEachPlaneMatch(
      target, samples, pose,
      [&](const PlaneMatch& m) {
        H += m.weight * m.jacobian * m.jacobian.transpose();
        g += m.weight * m.residual * m.jacobian;
        ++matched;
      },
      num_threads);
  return matched;
}

/** One damped Gauss-Newton step of \a pose against \a target, its increment (rotation
 *  vector, then translation) into \a delta. False, with \a pose unchanged, when fewer
 *  than six samples match or the step is not finite. */
bool step(const PointIndex& target, const VerificationSamples& samples, RigidPose& pose,
          Eigen::Matrix<double, 6, 1>& delta, int num_threads)
{
  Eigen::Matrix<double, 6, 6> H;
  Eigen::Matrix<double, 6, 1> g;
  if (sweep(target, samples, pose, H, g, num_threads) < 6)
    return false;
  // A little damping keeps directions the matches leave free (ground only, one wall
  // direction) where they are.
  H.diagonal().array() += 1e-6 * H.trace() + 1e-12;
  delta = -H.ldlt().solve(g);
  if (!delta.allFinite())
    return false;
  const Eigen::Matrix3d dR = expSo3(delta.head<3>());
  pose.R = dR * pose.R;
  pose.t = dR * pose.t + delta.tail<3>();
  return true;
}

/** refinePose, abandoned as soon as a step leaves the trust region of \a max_angle
 *  (radians) and \a max_shift (meters) around its center: \a start, or the pose a
 *  \a reach step put it at (that step skipped if it fails or leaves the region around
 *  \a start). The center is returned when a step leaves. */
RigidPose refine(const PointIndex& target, const VerificationSamples& samples,
                 const RigidPose& start, int iterations, double max_angle,
                 double max_shift, const PointIndex* reach, int num_threads)
{
  // The source's origin (its sensor) lands at t: how far it moved.
  const auto outside = [&](const RigidPose& pose, const RigidPose& center) {
    const Eigen::AngleAxisd turn(pose.R * center.R.transpose());
    return std::abs(turn.angle()) > max_angle || (pose.t - center.t).norm() > max_shift;
  };
  Eigen::Matrix<double, 6, 1> delta;
  RigidPose center = start;
  if (reach) {
    RigidPose reached = start;
    if (step(*reach, samples, reached, delta, num_threads) && !outside(reached, start))
      center = reached;
  }
  RigidPose pose = center;
  for (int it = 0; it < iterations; ++it) {
    if (!step(target, samples, pose, delta, num_threads))
      break;
    if (outside(pose, center))
      return center;
    if (delta.head<3>().norm() < kMinStepAngle &&
        delta.tail<3>().norm() < kMinStepShift)
      break;
  }
  return pose;
}

} // namespace

RigidPose refinePose(const PointIndex& target, const VerificationSamples& samples,
                     const RigidPose& start, int iterations)
{
  const double unbounded = std::numeric_limits<double>::infinity();
  return refine(target, samples, start, iterations, unbounded, unbounded, nullptr, 1);
}

RigidPose refinePoseWithin(const PointIndex& target, const VerificationSamples& samples,
                           const RigidPose& start, int iterations, double max_angle,
                           double max_shift, const PointIndex* reach, int num_threads)
{
  return refine(target, samples, start, iterations, max_angle, max_shift, reach,
                num_threads);
}

} // namespace pcl::phaser
