/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "priors/tilt_prior.h"
#include "so3/so3_correlation_grid.h"

#include <algorithm>
#include <cmath>

namespace pcl::phaser::detail {
namespace {

/** Least share of the orientation-histogram hypotheses tried within the prior (2 of
 * 10): within a 10 deg cone, KITTI and HDL-32 under 20 poses tilted up to 8 deg were
 * all found with 1 or 2, and 2 brings an align to about 0.6x the full search's time. */
constexpr double kTiltPriorOrientationShare = 0.2;

} // namespace

bool tiltPriorOn(const PhaserParameters& params)
{
  return params.max_tilt_deg > 0.0 && params.max_tilt_deg < 180.0;
}

double tiltOf(const Eigen::Matrix3d& R)
{
  return std::acos(std::clamp(R(2, 2), -1.0, 1.0));
}

int tiltConeOrientationCandidates(double max_tilt, int candidates)
{
  // Never fewer than the share of rotations the cone holds: wide cones keep them all.
  const double cone_share = 0.5 * (1.0 - std::cos(max_tilt));
  return static_cast<int>(
      std::ceil(std::max(kTiltPriorOrientationShare, cone_share) * candidates));
}

} // namespace pcl::phaser::detail
