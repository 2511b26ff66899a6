/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <Eigen/Core>

namespace pcl::phaser {

/** \brief Farthest a cloud's nearest point may lie from its viewpoint, as a share of
 *  its bounding-box diagonal, for the cloud to count as seen from there
 *  (ProjectionCenter::Automatic). The shared LiDAR scans measure 0-0.03 (nearest
 *  returns 0-2.2 m away, extents 60-95 m), and a 36 deg sector of one up to 0.1 and
 *  more (0.1 sent 21 of 180 such protocol trials to the centroid, 17 of them then
 *  failing); the bunny views in their frames 0.23-0.27, the Kinect frames 0.36 (both
 *  about their origins, which lie on their data); bun0 moved 1 m away 4, 100 m away
 *  400: what must go to the centroid is a cloud moved away from its origin. */
constexpr double kSensorFrameNearestShare = 0.5;

/** \brief True when \a points look like a scan seen from \a viewpoint: their nearest
 *  (of a strided subset of at most 20,000) lies within kSensorFrameNearestShare x
 *  their bounding-box diagonal of it. A scan's sensor surrounds itself with returns
 *  from near to far; an object scanned from afar, a depth camera's frustum or a cloud
 *  moved away from its frame origin leaves a gap about the viewpoint as large as
 *  itself. Non-finite points are ignored; false without finite points. */
bool looksSensorCentered(const Eigen::Matrix3Xd& points,
                         const Eigen::Vector3d& viewpoint);

/** \brief Farthest the nearest point may lie from a viewpoint on the data: the larger
 *  of this and kOnDataDiagonalShare x the bounding-box diagonal. The shared scans'
 *  nearest returns lie 0.5-2.2 m from their sensors and an aggregated map's 1.6 m
 *  from its first scan's; the same map moved 75 m off puts it 53 m away. */
constexpr double kOnDataDistance = 5.0;
constexpr double kOnDataDiagonalShare = 0.1;

/** \brief True when \a viewpoint lies on the data: the nearest of \a points (a strided
 *  subset of at most 20,000) is within max(kOnDataDistance m, kOnDataDiagonalShare x
 *  the bounding-box diagonal) of it. A scan's sensor origin is on its data; the origin
 *  of a map kept in a site frame hundreds of meters away is not. Non-finite points
 *  are ignored; false without finite points. */
bool originOnData(const Eigen::Matrix3Xd& points, const Eigen::Vector3d& viewpoint);

/** \brief Largest hiddenShare of a cloud seen from its viewpoint. A scanner sees no
 *  point behind another: about their origins the shared LiDAR scans measure
 *  0.002-0.04 (KITTI's mixed cells at depth edges the most), the Kinect frames and the
 *  milk carton 0.000-0.005; the bunny views about their frame origin, where no scanner
 *  stood, 0.078-0.29. Only from a viewpoint does the free-space test apply. */
constexpr double kMaxHiddenShare = 0.06;

/** \brief The share of \a points lying behind the nearest point of their direction
 *  cell from \a viewpoint (Driscoll-Healy, B = 256: 0.35 x 0.7 deg) by more than 5 %
 *  of the range plus 1 % of the bounding-box diagonal (noise); 0 without points. */
double hiddenShare(const Eigen::Matrix3Xd& points, const Eigen::Vector3d& viewpoint);

} // namespace pcl::phaser
