/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "pipeline/tilt_prior.h"

namespace pcl::phaser {
namespace detail {
namespace {

/** Least share of the orientation-histogram hypotheses tried within the prior (2 of
 * 10): within a 10 deg cone, KITTI and HDL-32 under 20 poses tilted up to 8 deg were
 * all found with 1 or 2, and 2 brings an align to about 0.6x the full search's time. */
constexpr double kTiltPriorOrientationShare = 0.2;

double maxTilt(const PhaserParameters& params)
{
  return params.max_tilt_deg * M_PI / 180.0;
}

/** The prior is on below 180 degrees: at 180 every rotation is within it. */
bool priorOn(const PhaserParameters& params)
{
  return params.max_tilt_deg > 0.0 && params.max_tilt_deg < 180.0;
}

} // namespace

double tiltOf(const Eigen::Matrix3d& R)
{
  return std::acos(std::clamp(R(2, 2), -1.0, 1.0));
}

int tiltPriorRows(const PhaserParameters& params, int output_bandwidth)
{
  if (!priorOn(params))
    return 0;
  return betaRowsForTilt(output_bandwidth, maxTilt(params));
}

StageParameters withTiltPrior(const StageParameters& params)
{
  StageParameters out = params;
  if (!priorOn(params))
    return out;
  // Never fewer than the share of rotations the cone holds: wide cones keep them all.
  const double cone_share = 0.5 * (1.0 - std::cos(maxTilt(params)));
  out.orientation_candidates =
      static_cast<int>(std::ceil(std::max(kTiltPriorOrientationShare, cone_share) *
                                 params.orientation_candidates));
  return out;
}

bool withinTiltPrior(const PhaserParameters& params, const Eigen::Matrix3d& R)
{
  return !priorOn(params) ||
         tiltOf(R) <= maxTilt(params) + M_PI / (2.0 * params.bandwidth);
}

void keepWithinTiltPrior(const PhaserParameters& params, RigidPose& pose,
                         PhaserResult& result)
{
  if (withinTiltPrior(params, pose.R))
    return;
  PhaserDiagnostics& diagnostics = result.diagnostics;
  int best = -1;
  for (std::size_t k = 0; k < diagnostics.hypotheses.size(); ++k) {
    const Hypothesis& h = diagnostics.hypotheses[k];
    if (withinTiltPrior(params, h.rotation) &&
        (best < 0 ||
         h.verification.rank >
             diagnostics.hypotheses[static_cast<std::size_t>(best)].verification.rank))
      best = static_cast<int>(k);
  }
  if (best >= 0) {
    const Hypothesis& h = diagnostics.hypotheses[static_cast<std::size_t>(best)];
    pose.R = h.rotation;
    pose.t = h.translation;
    diagnostics.verification = h.verification;
    result.chosen_hypothesis = best;
  } else {
    EulerZYZ e = eulerFromRotation(pose.R);
    e.beta = std::min(e.beta, maxTilt(params));
    pose.R = rotationFromEuler(e);
  }
  diagnostics.verified = false;
}

} // namespace detail
} // namespace pcl::phaser
