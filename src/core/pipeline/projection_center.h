/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <Eigen/Core>

namespace pcl::phaser {

/** \brief Fraction of the sphere's area (0..1) in whose directions \a points are seen
 *  from \a viewpoint: the area of the 16 x 16 Driscoll-Healy cells (B = 8, ~11 deg)
 *  that hold at least one point in a thousand. Non-finite points and points at the
 *  viewpoint are ignored; 0 when none is left.
 *
 * A scan in its sensor frame surrounds its origin: a spinning LiDAR sees a full turn of
 * azimuth (HDL-64E: 0.23 of the sphere, HDL-32E: 0.3). An object scanned from afar, a
 * depth camera's frustum or a cloud moved away from its origin covers a small cap.
 */
double viewCoverage(const Eigen::Matrix3Xd& points, const Eigen::Vector3d& viewpoint);

/** \brief Fraction of \a points (0..1) seen from \a viewpoint within 45 deg of the
 *  poles of their band: the axis around which their directions concentrate least (the
 *  smallest eigenvector of the directions' scatter matrix). Rotation-invariant.
 *
 * A spinning LiDAR sees nothing there (vertical field of view within +-45 deg); a room
 * seen from inside, or a terrestrial scanner, sees floor and ceiling. */
double polarFraction(const Eigen::Matrix3Xd& points, const Eigen::Vector3d& viewpoint);

/** \brief Least viewCoverage and most polarFraction of a cloud in its sensor frame
 *  (ProjectionCenter::Automatic), set between the values of the shared scans. */
constexpr double kSensorFrameCoverage = 0.2;
constexpr double kSensorFramePolarFraction = 0.005;

/** \brief True when \a points look like a spinning-LiDAR scan seen from its sensor at
 *  \a viewpoint: they surround it (kSensorFrameCoverage) in a band that leaves the
 *  poles empty (kSensorFramePolarFraction). */
bool looksSensorCentered(const Eigen::Matrix3Xd& points,
                         const Eigen::Vector3d& viewpoint);

} // namespace pcl::phaser
