/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: how the position prior (PhaserParameters::region) restricts
// the search; allowed_poses.h guards the answer.
#include "spatial/spatial_correlation.h"
#include "spatial/spatial_single.h"

#include <pcl_phaser/core/parameters.h>
#include <pcl_phaser/core/types.h>

#include <Eigen/Core>

namespace pcl::phaser::detail {

/** \brief Where the source's sensor may be, in the target's frame. */
struct SearchRegion {
  Eigen::Vector3d center = Eigen::Vector3d::Zero(); ///< meters
  double radius = 0.0;                              ///< meters, > 0
  double reach = 0.0; ///< meters: target points farther from center are left out
  bool operator==(const SearchRegion& other) const
  {
    return center == other.center && radius == other.radius && reach == other.reach;
  }
  bool operator!=(const SearchRegion& other) const { return !(*this == other); }
};

/** \brief The search region of \a region; the sensor range, when not set, from \a moved
 *  (the source after the guess) about \a sensor (its origin after the guess). */
SearchRegion searchRegion(const Region& region, const Eigen::Matrix3Xd& moved,
                          const Eigen::Vector3d& sensor);

/** \brief A cloud cut to a region, relative to its center. */
struct RegionCloud {
  Eigen::Matrix3Xd points;
  ChannelValues channels;
};

/** \brief The points of \a points (and their \a channels) within region.reach of its
 *  center, minus the center.
 *  \throws InvalidArgument when fewer than 100 points remain. */
RegionCloud cropToRegion(const Eigen::Matrix3Xd& points, const ChannelValues& channels,
                         const SearchRegion& region);

/** \brief \a cloud reduced to the centroid (points and channel values) of each cube of
 *  the finest cell the target model uses on the grid \a grid_size / \a voxel_size
 *  (PhaserParameters) sizes for it: a dense map prepares as fast as a scan. */
RegionCloud thinForModel(const RegionCloud& cloud, int grid_size, double voxel_size);

/** \brief Lowers every lag of \a correlation whose shift is farther than \a radius
 *  from \a center (meters, the shift's space) to the volume's minimum, so no peak is
 *  found there. */
void keepShiftsWithin(SpatialVolume& correlation, const Eigen::Vector3d& center,
                      double radius);
/** \brief keepShiftsWithin of a single-precision volume (pass 1). */
void keepShiftsWithin(SpatialVolumeF& correlation, const Eigen::Vector3d& center,
                      double radius);

} // namespace pcl::phaser::detail
