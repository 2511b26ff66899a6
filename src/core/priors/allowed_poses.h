/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: the priors of PhaserParameters (region, max_tilt_deg) as the
// poses they allow, what the search asks of them, and the guard that no other pose is
// returned as converged.
#include "priors/region.h"

#include <pcl_phaser/core/parameters.h>
#include <pcl_phaser/core/result.h>

#include <Eigen/Core>

#include <limits>
#include <optional>
#include <string>

namespace pcl::phaser::detail {

/** \brief The poses T (p_target = T p_source, the guess composed) the priors allow. */
struct AllowedPoses {
  std::optional<SearchRegion> region; ///< where the source's sensor, T's origin, may be
  /** \brief Radians: the largest tilt of T's rotation relative to the guess's; infinity
   *  without a gravity prior. */
  double max_tilt = std::numeric_limits<double>::infinity();
  /** \brief Radians: what a tilt may exceed max_tilt by (the refinements' drift). */
  double tilt_slack = 0.0;
  Eigen::Matrix3d guess_rotation = Eigen::Matrix3d::Identity();

  /** \brief Empty when \a T is allowed, else why not. */
  std::string refusal(const Eigen::Matrix4d& T) const;

  /** \brief Meters: the longest shift the search of the first pass may take, the
   *  region's radius and one \a coarse_voxel (the source's sensor sits at the centered
   *  origin, the region's center at the target's); infinity without a region. */
  double shiftBound(double coarse_voxel) const;
  /** \brief Beta rows of a (2 Bo)^3 SO(3) grid of \a output_bandwidth Bo the search
   *  correlates (betaRowsForTilt of max_tilt); 0, the whole grid, without a tilt cone.
   */
  int rotationRows(int output_bandwidth) const;
  /** \brief Of \a requested orientation-histogram candidates, those the search tries
   *  (tiltConeOrientationCandidates); all without a tilt cone. */
  int orientationCandidates(int requested) const;
};

/** \brief The poses \a params allow for the source \a moved (its points after \a
 * guess).
 */
AllowedPoses allowedPoses(const PhaserParameters& params, const Eigen::Matrix3Xd& moved,
                          const Eigen::Matrix4d& guess);

/** \brief Keeps \a result within \a allowed: a pose outside is replaced by the
 *  highest-ranked allowed hypothesis (else moved to the nearest allowed pose) and is
 *  then neither verified nor converged; diagnostics.refusal says why. */
void keepAllowed(PhaserResult& result, const AllowedPoses& allowed);

} // namespace pcl::phaser::detail
