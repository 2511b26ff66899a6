/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Clouds and comparisons shared by the translation stage's tests.
 */
#pragma once

#include "spatial/spatial_correlation.h"

#include <cstring>
#include <random>

namespace pcl::phaser::test {

/** Uniform random points in the box [-hx, hx] x [-hy, hy] x [-hz, hz]. */
inline Eigen::Matrix3Xd randomBox(int count, const Eigen::Vector3d& half, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3Xd points(3, count);
  for (int i = 0; i < count; ++i)
    points.col(i) << u(rng) * half.x(), u(rng) * half.y(), u(rng) * half.z();
  return points;
}

/** A LiDAR-like 40 x 30 x 8 m box of points. */
inline Eigen::Matrix3Xd sceneBox(int count, unsigned seed)
{
  return randomBox(count, Eigen::Vector3d(20.0, 15.0, 4.0), seed);
}

inline SpatialVolume zeroVolume(const Eigen::Vector3i& dims, double voxel = 0.5)
{
  SpatialVolume v;
  v.grid.dims = dims;
  v.grid.voxel_size = voxel;
  v.values.assign(v.grid.size(), 0.0);
  return v;
}

/** A volume of 0.25 m voxels holding standard normal values. */
inline SpatialVolume randomVolume(const Eigen::Vector3i& dims, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> n;
  SpatialVolume v;
  v.grid.dims = dims;
  v.grid.voxel_size = 0.25;
  v.values.assign(v.grid.size(), 0.0);
  for (double& x : v.values)
    x = n(rng);
  return v;
}

inline bool bitIdentical(const SpatialRealArray& a, const SpatialRealArray& b)
{
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

/** correlateSpectra followed by findSpatialPeak. */
inline SpatialCorrelationResult
correlateSpatial(const SpatialSpectrum& target, const SpatialSpectrum& source,
                 SpatialPeakRefinement refinement = SpatialPeakRefinement::kGaussian)
{
  return findSpatialPeak(correlateSpectra(target, source), refinement);
}

} // namespace pcl::phaser::test
