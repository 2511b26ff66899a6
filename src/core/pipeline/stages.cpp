/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The order of the stages of one estimate.
 */
#include "channels/cloud_signals.h"
#include "pipeline/final_pose.h"
#include "pipeline/hypotheses.h"
#include "pipeline/passes.h"
#include "pipeline/stages.h"
#include "pipeline/verdict.h"

namespace pcl::phaser::detail {

RigidPose estimateCentered(const TargetModel& target, const Eigen::Matrix3Xd& points,
                           const StageSettings& settings, const AllowedPoses& allowed,
                           const ChannelValues& raw_channels, PhaserResult& result)
{
  const ChannelValues channels = normalizeChannels(raw_channels, points.cols());
  PhaserDiagnostics& diagnostics = result.diagnostics;
  StageTimes& times = diagnostics.times;
  diagnostics.verification_radius = target.index.radius();
  const SourceContext source =
      sourceContext(target, points, channels, settings, allowed, times);
  GlobalSearch search = globalSearch(source, times);
  result.chosen_hypothesis = search.chosen;
  diagnostics.hypotheses = std::move(search.hypotheses);
  diagnostics.passes = 1;
  Pose pose = search.decided
                  ? search.pose
                  : reprojectionPasses(source, search.pose, diagnostics.passes, times);
  pose = refineFinalPose(source, pose, search.decided, result);
  judgeFinalPose(source, pose, result);
  return pose;
}

} // namespace pcl::phaser::detail
