/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "sphere/spherical_harmonics.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl::phaser {

/** \brief Planar patches of a cloud: per voxel with enough points, the normal of the
 *  points' covariance (its smallest eigenvector, turned towards the viewpoint) and a
 *  weight that is large for flat patches, (l1 - l0) / l2 of the eigenvalues
 *  l0 <= l1 <= l2, in [0, 1]. */
struct SurfacePatches {
  Eigen::Matrix3Xd normals;       ///< unit normals, 3 x m
  Eigen::VectorXd weights;        ///< planarity in [0, 1], m
  std::vector<std::int64_t> keys; ///< voxelKey of each patch's voxel, m
  double voxel_size = 0.0;        ///< edge of the voxels, meters
  /** \brief Median RMS distance of the patches' points from their plane, sqrt(l0 / n),
   *  meters (0 without patches). */
  double thickness = 0.0;
};

/** \brief The planar patches of \a points in voxels of edge \a voxel_size (meters)
 *  holding at least \a min_points (>= 3) points, normals turned towards \a viewpoint.
 */
SurfacePatches surfacePatches(const Eigen::Matrix3Xd& points, double voxel_size,
                              const Eigen::Vector3d& viewpoint, int min_points = 6);

/** \brief Spectrum of the orientation histogram of \a patches (an extended Gaussian
 *  image): the square root of the patch weights summed per cell of their normal, per
 *  unit solid angle, de-meaned and low-passed. It does not move with the sensor, so
 *  the SO(3) correlation of two scans' spectra peaks at their relative rotation.
 *  \throws InvalidArgument on a bandwidth outside 1..256 */
SphericalSpectrum orientationSpectrum(const SurfacePatches& patches, int bandwidth,
                                      int num_threads = 1);

/** \brief The normal of the patch whose voxel holds each of \a points (3 x m), or
 *  zero where that voxel has no patch. */
Eigen::Matrix3Xd patchNormalsAt(const SurfacePatches& patches,
                                const Eigen::Matrix3Xd& points);

/** \brief Weights of \a samples (3 x m) that balance surface orientations, as
 *  normal-space sampling does for ICP: samples are counted per cell (8 x 8) of their
 *  patch's normal, those without a patch in one more class, and each weighs 1 / max(its
 *  class's count, 2 % of m), normalized to sum 1, so the ground no longer outvotes the
 *  walls that fix the pose. */
Eigen::VectorXd orientationWeights(const SurfacePatches& patches,
                                   const Eigen::Matrix3Xd& samples);

} // namespace pcl::phaser
