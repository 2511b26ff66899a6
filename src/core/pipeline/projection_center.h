/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <Eigen/Core>

namespace pcl::phaser {

/** \brief Fraction of the sphere's area (0..1) in whose directions \a points are seen
 *  from \a viewpoint: the 16 x 16 Driscoll-Healy cells (B = 8) holding at least one
 *  point in a thousand; non-finite points and points at the viewpoint are ignored.
 *  A spinning LiDAR covers a full turn of azimuth (HDL-64E: 0.23, HDL-32E: 0.3); an
 *  object scanned from afar or a depth camera's frustum, a small cap. */
double viewCoverage(const Eigen::Matrix3Xd& points, const Eigen::Vector3d& viewpoint);

/** \brief Fraction of \a points (0..1) seen from \a viewpoint within 45 deg of the
 *  poles of their band (the smallest eigenvector of the directions' scatter). A
 *  spinning LiDAR sees nothing there; a room seen from inside sees floor and ceiling.
 */
double polarFraction(const Eigen::Matrix3Xd& points, const Eigen::Vector3d& viewpoint);

/** \brief Least viewCoverage and most polarFraction of a cloud in its sensor frame
 *  (ProjectionCenter::Automatic), set between the values of the shared scans. */
constexpr double kSensorFrameCoverage = 0.2;
constexpr double kSensorFramePolarFraction = 0.005;

/** \brief True when \a points look like a spinning-LiDAR scan seen from its sensor at
 *  \a viewpoint: they surround it in a band that leaves the poles empty. */
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

} // namespace pcl::phaser
