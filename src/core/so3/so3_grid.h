/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <Eigen/Core>

namespace pcl::phaser {

/** \brief ZYZ Euler angles: R = Rz(alpha) Ry(beta) Rz(gamma), beta in [0, pi]. */
struct EulerZYZ {
  double alpha = 0.0;
  double beta = 0.0;
  double gamma = 0.0;
};

/** \brief Rz(alpha) Ry(beta) Rz(gamma) with right-handed, active elementary rotations.
 */
Eigen::Matrix3d rotationFromEuler(const EulerZYZ& e);

/** \brief Inverse of rotationFromEuler with beta in [0, pi] (not Eigen's eulerAngles,
 * which may return a negative beta). At the poles gamma is set to 0. */
EulerZYZ eulerFromRotation(const Eigen::Matrix3d& R);

/** \brief A sample of the (2Bo)^3 Euler grid: beta index j, alpha index a, gamma index
 * c. Its flat index is (j * N + a) * N + c with N = 2 Bo. */
struct So3GridIndex {
  int beta = 0;
  int alpha = 0;
  int gamma = 0;
};

/** \brief alpha = pi a / Bo, beta = pi (2j+1) / (4 Bo), gamma = pi c / Bo. */
EulerZYZ gridEuler(const So3GridIndex& index, int output_bandwidth);

/** \brief Geodesic angle between two rotations, in radians. */
double rotationDistance(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B);

} // namespace pcl::phaser
