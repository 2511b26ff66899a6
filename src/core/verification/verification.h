/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "index/point_index.h"

#include <pcl_phaser/core/result.h>

#include <Eigen/Core>

#include <vector>

namespace pcl::phaser {

/** \brief What the target's sensor saw: per direction cell of the Driscoll-Healy grid
 *  of bandwidth B about its sensor origin, the nearest return in the cell and its 8
 *  neighbors; 0 marks a cell without returns. */
struct FreeSpace {
  int bandwidth = 0;
  std::vector<double> nearest; ///< 4 B^2 cells
  double margin = 0.0;         ///< meters a sample must be in front to violate
};

/** \brief FreeSpace of \a points (3 x n, relative to the sensor origin).
 *  \param[in] bandwidth B of the direction cells (1..256) \param[in] margin meters */
FreeSpace freeSpace(const Eigen::Matrix3Xd& points, int bandwidth, double margin,
                    int num_threads = 1);

/** \brief The weighted share of \a samples (3 x m, moved by q = R s + t into the frame
 *  of \a seen) closer along a ray than the nearest return around it by more than
 *  seen.margin; 0 for an empty FreeSpace or sample set. */
double freeSpaceViolation(const FreeSpace& seen, const Eigen::Matrix3Xd& samples,
                          const Eigen::VectorXd& weights, const Eigen::Matrix3d& R,
                          const Eigen::Vector3d& t, int num_threads = 1);

/** \brief Per sample: 1 when it violates the free space of \a seen (as
 *  freeSpaceViolation), else 0. */
std::vector<double> sampleViolations(const FreeSpace& seen,
                                     const Eigen::Matrix3Xd& samples,
                                     const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                                     int num_threads = 1);

/** \brief Samples with what verifyPose needs besides their position. */
struct VerificationSamples {
  Eigen::Matrix3Xd points;  ///< 3 x m, e.g. voxelCentroids
  Eigen::VectorXd weights;  ///< m, e.g. orientationWeights
  Eigen::Matrix3Xd normals; ///< empty, or 3 x m (zero: none), e.g. patchNormalsAt
};

/** \brief Cosine of the largest angle between the rotated normal of a sample and the
 *  normal of a target point that still match (about 45 deg). */
constexpr double kMinNormalCosine = 0.7;

/** \brief Per sample under the pose (R, t): max(1e-12, 1 - d^2 / r^2) when a target
 *  point lies within the index radius r at distance d (with an agreeing normal when
 *  both have normals), else 0. Deterministic for any \a num_threads. */
std::vector<double> sampleCloseness(const PointIndex& target,
                                    const VerificationSamples& samples,
                                    const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                                    int num_threads = 1);

/** \brief Verifies the pose q_t = R q_s + t of \a samples against \a target. When both
 *  have normals only target points whose normal agrees with the sample's rotated one
 *  (kMinNormalCosine) count; Verification::constraint is normalized by all samples with
 *  a \a free_space, by the inliers without. An empty sample set or index gives zeros. Deterministic
 *  for any \a num_threads. \throws InvalidArgument unless there is one weight (and
 *  normal, if any) per sample. */
Verification verifyPose(const PointIndex& target, const VerificationSamples& samples,
                        const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                        int num_threads = 1, const FreeSpace* free_space = nullptr);

} // namespace pcl::phaser
