/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Checks and circular-index helpers shared by the 3-D correlation, its peak and the
 * peak's covariance.
 */
#pragma once

#include "spatial/spatial_correlation.h"
#include "support/error.h"

#include <algorithm>
#include <cmath>
#include <omp.h>
#include <string>

namespace pcl::phaser {
namespace detail {

inline int resolveThreads(int num_threads)
{
  if (num_threads < 0)
    throw InvalidArgument("num_threads must be >= 0 (0 = OpenMP default), got " +
                          std::to_string(num_threads));
  return num_threads == 0 ? std::max(1, omp_get_max_threads()) : num_threads;
}

inline void checkGrid(const SpatialGrid& grid, const char* what)
{
  if ((grid.dims.array() < 1).any() || !(grid.voxel_size > 0.0) ||
      !std::isfinite(grid.voxel_size) || !grid.origin.allFinite())
    throw InvalidArgument(std::string(what) +
                          ": grid needs dims >= 1, a finite voxel_size > 0 and a "
                          "finite origin");
}

/** \a Volume: SpatialVolume, or SpatialVolumeF (single precision). */
template <typename Volume>
void checkVolume(const Volume& volume, const char* what)
{
  checkGrid(volume.grid, what);
  if (volume.values.size() != volume.grid.size())
    throw InvalidArgument(std::string(what) + ": values.size() " +
                          std::to_string(volume.values.size()) + " != grid.size() " +
                          std::to_string(volume.grid.size()));
}

/** Signed lag of index i on a circular axis of length n: i, or i - n past n / 2. */
inline int wrapLag(int i, int n)
{
  return i > n / 2 ? i - n : i;
}

inline int wrapIndex(int i, int n)
{
  const int r = i % n;
  return r < 0 ? r + n : r;
}

/** Neighbors below this fraction of the peak are FFT round-off rather than peak shape:
 *  the sub-voxel fit then uses the raw values, not their logs. */
constexpr double kLogFloor = 1e-6;

/** The value of \a c at the index \a p, wrapped around. */
template <typename Volume>
double valueAtWrapped(const Volume& c, const Eigen::Vector3i& p)
{
  const Eigen::Vector3i& n = c.grid.dims;
  return c.values[c.grid.flatIndex(wrapIndex(p.x(), n.x()), wrapIndex(p.y(), n.y()),
                                   wrapIndex(p.z(), n.z()))];
}

/** The values before \a peak on \a axis, at it and after it (wrapped). */
template <typename Volume>
Eigen::Vector3d axisValues(const Volume& c, const Eigen::Vector3i& peak, int axis)
{
  Eigen::Vector3i before = peak, after = peak;
  --before[axis];
  ++after[axis];
  return {valueAtWrapped(c, before), valueAtWrapped(c, peak), valueAtWrapped(c, after)};
}

} // namespace detail
} // namespace pcl::phaser
