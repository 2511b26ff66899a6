/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: what every stage of one estimate reads of the source, beside
// the target model, the settings and the priors.
#include "channels/surface_orientation.h"
#include "pipeline/target_model.h"
#include "priors/allowed_poses.h"
#include "verification/pose_verifier.h"

#include <pcl_phaser/core/result.h>

namespace pcl::phaser::detail {

/** Everything one estimate needs about the source (centered coordinates). */
struct SourceContext {
  const TargetModel& target;
  const Eigen::Matrix3Xd& points;
  const ChannelValues& channels; ///< normalized
  const StageSettings& settings;
  const AllowedPoses& allowed;    ///< asked for the search's bounds
  VerificationSamples samples;    ///< evenly spaced source points for verifyPose
  VerificationSamples polish;     ///< samples thinned for the polish's steps
  SurfacePatches patches;         ///< planar patches of the source (coarse voxels)
  FreeSpace free_space;           ///< what the source's sensor saw through
  Eigen::Matrix3Xd coarse_points; ///< thinned for the pass-1 (binary) occupancy grids
  /** Poses are chosen and claimed by verification; about centroids of clouds with about
   *  one point per verification cube (sparser than its radius) the peak rule decides.
   */
  bool verification = true;

  /** Verified without free space: objects, about their frame origin or centroid. */
  bool objects() const { return verification && !settings.mode.viewpoints; }
  /** Whether verification tells poses apart: dense enough clouds (verification),
   *  thin surfaces in both (else about centroids the peak rule decides). */
  bool canVerify() const;
  /** What verifyBothWays and refineOnSamples read (pointers into this and the target,
   *  valid while both live): the free spaces about viewpoints only. */
  VerificationClouds verificationClouds() const;
};

/** The source context of \a points (relative to the source's projection center) and
 *  its normalized \a channels against \a target; its time into \a times. */
SourceContext sourceContext(const TargetModel& target, const Eigen::Matrix3Xd& points,
                            const ChannelValues& channels,
                            const StageSettings& settings, const AllowedPoses& allowed,
                            StageTimes& times);

} // namespace pcl::phaser::detail
