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
  /** \brief Median over the patches of the RMS distance of their points from their
   *  plane (sqrt(l0 / n)), meters: the surface thickness that noise gives a scan. 0
   *  without patches. */
  double thickness = 0.0;
};

/** \brief The planar patches of \a points in voxels of edge \a voxel_size (meters,
 *  > 0) that hold at least \a min_points points (>= 3).
 *  \param[in] viewpoint normals are turned to face it (the sensor), so a wall seen
 *  from the same side gives the same normal in both scans */
SurfacePatches surfacePatches(const Eigen::Matrix3Xd& points, double voxel_size,
                              const Eigen::Vector3d& viewpoint, int min_points = 6);

/** \brief Spectrum of the orientation histogram of \a patches on the sphere (an
 *  extended Gaussian image): each patch adds its weight to the Driscoll-Healy cell of
 *  its normal; the square root of each cell's sum (so the ground does not drown the
 *  walls), de-meaned over the sphere, is transformed. The histogram does not move with
 *  the sensor: for two scans of one place it is the same function up to the relative
 *  rotation, q_t = R q_s, and the SO(3) correlation of the two spectra peaks at R.
 *  \param[in] bandwidth B (1..256) \param[in] num_threads worker threads
 *  \throws InvalidArgument on an illegal bandwidth */
SphericalSpectrum orientationSpectrum(const SurfacePatches& patches, int bandwidth,
                                      int num_threads = 1);

/** \brief The normal of the patch whose voxel holds each of \a points (3 x m), or
 *  zero where that voxel has no patch. */
Eigen::Matrix3Xd patchNormalsAt(const SurfacePatches& patches,
                                const Eigen::Matrix3Xd& points);

/** \brief Weights of verification samples that balance surface orientations, as
 *  normal-space sampling does for ICP (Rusinkiewicz and Levoy, 3DIM 2001): each sample
 *  takes the normal of the patch whose voxel holds it, samples are counted per
 *  orientation cell (a 8 x 8 Driscoll-Healy grid; samples without a patch form one more
 *  class), and a sample weighs 1 / sqrt(count of its class), normalized to sum 1. So
 *  the ground, a large share of every outdoor scan that matches under any yaw, no
 *  longer outvotes the walls that fix the pose.
 *  \param[in] patches from surfacePatches \param[in] samples 3 x m */
Eigen::VectorXd orientationWeights(const SurfacePatches& patches,
                                   const Eigen::Matrix3Xd& samples);

} // namespace pcl::phaser
