/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "priors/allowed_poses.h"
#include "priors/tilt_prior.h"
#include "so3/so3_correlation_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace pcl::phaser::detail {
namespace {

/** \a T's rotation relative to the guess's: the rotation the search estimated. */
Eigen::Matrix3d searched(const AllowedPoses& allowed, const Eigen::Matrix4d& T)
{
  return T.topLeftCorner<3, 3>() * allowed.guess_rotation.transpose();
}

/** \a T moved to the nearest allowed pose: its tilt clamped, its sensor into the
 *  region. */
Eigen::Matrix4d nearestAllowed(const AllowedPoses& allowed, Eigen::Matrix4d T)
{
  if (std::isfinite(allowed.max_tilt)) {
    EulerZYZ e = eulerFromRotation(searched(allowed, T));
    e.beta = std::min(e.beta, allowed.max_tilt);
    T.topLeftCorner<3, 3>() = rotationFromEuler(e) * allowed.guess_rotation;
  }
  if (allowed.region) {
    const SearchRegion& region = *allowed.region;
    const Eigen::Vector3d offset = T.topRightCorner<3, 1>() - region.center;
    if (offset.norm() > region.radius)
      T.topRightCorner<3, 1>() =
          region.center + offset * (region.radius / offset.norm());
  }
  return T;
}

} // namespace

std::string AllowedPoses::refusal(const Eigen::Matrix4d& T) const
{
  char text[160];
  const double tilt = tiltOf(searched(*this, T));
  if (tilt > max_tilt + tilt_slack) {
    std::snprintf(text, sizeof(text),
                  "the pose tilts %.1f deg, beyond max_tilt_deg %.1f",
                  tilt * 180.0 / M_PI, max_tilt * 180.0 / M_PI);
    return text;
  }
  const double distance =
      region ? (T.topRightCorner<3, 1>() - region->center).norm() : 0.0;
  if (region && distance > region->radius) {
    std::snprintf(text, sizeof(text),
                  "the pose puts the sensor %.2f m from the region's center, beyond "
                  "its radius %.2f m",
                  distance, region->radius);
    return text;
  }
  return {};
}

double AllowedPoses::shiftBound(double coarse_voxel) const
{
  return region ? region->radius + coarse_voxel
                : std::numeric_limits<double>::infinity();
}

int AllowedPoses::rotationRows(int output_bandwidth) const
{
  return std::isfinite(max_tilt) ? betaRowsForTilt(output_bandwidth, max_tilt) : 0;
}

int AllowedPoses::orientationCandidates(int requested) const
{
  return std::isfinite(max_tilt) ? tiltConeOrientationCandidates(max_tilt, requested)
                                 : requested;
}

AllowedPoses allowedPoses(const PhaserParameters& params, const Eigen::Matrix3Xd& moved,
                          const Eigen::Matrix4d& guess)
{
  AllowedPoses allowed;
  allowed.guess_rotation = guess.topLeftCorner<3, 3>();
  if (params.region)
    allowed.region = searchRegion(*params.region, moved, guess.topRightCorner<3, 1>());
  if (tiltPriorOn(params)) {
    allowed.max_tilt = params.max_tilt_deg * M_PI / 180.0;
    allowed.tilt_slack = M_PI / (2.0 * params.bandwidth); // half an SO(3) grid cell
  }
  return allowed;
}

void keepAllowed(PhaserResult& result, const AllowedPoses& allowed)
{
  PhaserDiagnostics& diagnostics = result.diagnostics;
  std::string refusal = allowed.refusal(result.transformation);
  if (refusal.empty())
    return;
  int best = -1;
  const std::vector<Hypothesis>& hypotheses = diagnostics.hypotheses;
  for (std::size_t k = 0; k < hypotheses.size(); ++k)
    if (allowed.refusal(hypotheses[k].transformation).empty() &&
        (best < 0 ||
         hypotheses[k].verification.rank > hypotheses[best].verification.rank))
      best = static_cast<int>(k);
  if (best >= 0) {
    result.transformation = hypotheses[best].transformation;
    result.chosen_hypothesis = best;
    diagnostics.verification = hypotheses[best].verification;
    refusal += "; returned the best hypothesis within the priors";
  } else {
    result.transformation = nearestAllowed(allowed, result.transformation);
    refusal += "; returned the nearest pose within the priors";
  }
  diagnostics.refusal = std::move(refusal);
  diagnostics.verified = false;
  result.converged = false;
}

} // namespace pcl::phaser::detail
