/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "verification/verification.h"

#include <Eigen/Core>

namespace pcl::phaser {

/** \brief A rigid pose q_t = R q_s + t. */
struct RigidPose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

/** \brief Local refinement of a pose that verifyPose scores: Gauss-Newton steps on the
 *  point-to-plane distances of the samples to their nearest target point within the
 *  index radius r (with an agreeing normal), each weighted by the sample weight times
 *  (1 - d^2 / r^2)^2, the derivative of the closeness that PoseVerification::score
 *  averages. It climbs that score from a pose whose samples already partly touch the
 *  target (a verified hypothesis, about half a coarse voxel off); it does not search.
 *  The steps stop early when one turns less than 1e-4 rad and moves less than 1 mm.
 *  Deterministic (serial sums in sample order).
 *  \param[in] target target points with normals (samples without a matched normal
 *  are skipped) \param[in] samples source samples with weights and normals
 *  \param[in] start initial pose \param[in] iterations Gauss-Newton steps, >= 0
 *  \return the refined pose; \a start when fewer than six samples match */
RigidPose refinePose(const PointIndex& target, const VerificationSamples& samples,
                     const RigidPose& start, int iterations);

/** \brief refinePose within a trust region: \a start as soon as a step turns the pose
 *  by more than \a max_angle (radians) or moves the sensor by more than \a max_shift
 *  (meters) from it (a climb that far left the basin it started in).
 *  \param[in] reach null, or the same target indexed at a larger radius: then one step
 *  against it comes first and re-centers the climb. It reaches samples that a start
 *  about that radius off puts beyond \a target's radius, so the \a iterations steps
 *  against \a target start in the basin of the pose the start approximates; the trust
 *  region is then around the pose it reached, which is returned if a later step leaves
 *  it. The reach step is skipped when fewer than six samples match or it leaves the
 *  region around \a start. */
RigidPose refinePoseWithin(const PointIndex& target, const VerificationSamples& samples,
                           const RigidPose& start, int iterations, double max_angle,
                           double max_shift, const PointIndex* reach = nullptr);

} // namespace pcl::phaser
