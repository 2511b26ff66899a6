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

} // namespace pcl::phaser
