/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/core/so3_correlation.h>
#include <pcl_phaser/core/spatial_correlation.h>

#include <Eigen/Core>

#include <vector>

namespace pcl_phaser {

/** \brief A rotation of the SO(3) grid and the correlation there. */
struct RotationSample {
  Eigen::Matrix3d rotation;
  double value;
};

/** \brief The (2r+1)^3 block of grid samples around \a peak, a true 3-D neighbourhood:
 *  alpha and gamma wrap modulo N, and a beta index beyond the poles reflects, because
 *  Rz(a) Ry(-b) Rz(c) = Rz(a + pi) Ry(b) Rz(c - pi): index j < 0 reads row -1 - j and
 *  j >= N reads row 2N - 1 - j, both at (a + Bo, c - Bo). Near the poles several
 *  samples may be (almost) the same rotation; they are kept, each with its value.
 *  \param[in] grid the correlation on the Euler grid
 *  \param[in] peak centre of the block
 *  \param[in] radius r >= 0 */
std::vector<RotationSample> rotationNeighbourhood(const So3CorrelationGrid& grid,
                                                  const So3GridIndex& peak, int radius);

/** \brief Up to \a count grid peaks in decreasing order of C, in the upper half of the
 *  value range, that are local maxima of their 3x3x3 neighbourhood and lie more than \a
 * min_separation radians from every peak already taken (ties by lowest flat index:
 * deterministic). \param[in] grid the correlation on the Euler grid \param[in] count
 * how many peaks at most \param[in] min_separation geodesic distance between distinct
 * peaks, in radians */
std::vector<So3GridIndex> distinctPeaks(const So3CorrelationGrid& grid, int count,
                                        double min_separation);

/** \brief A Gaussian on translations, in metres. */
struct TranslationGaussian {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

/** \brief Weighted Gaussian over the (2r+1)^3 lags around the integer peak of a spatial
 *  correlation (paper eq. 15). Weights are the correlation above the lowest value of
 * the block, normalised to sum 1, so they describe the shape of the peak rather than
 * the size of the window; lags wrap around. The mean is relative to the lag-0 shift of
 * the volume (its origin), in metres, like SpatialCorrelationResult::shift. \param[in]
 * correlation a volume from correlateSpectra \param[in] peak integer peak index
 *  \param[in] radius r >= 1 */
TranslationGaussian translationGaussian(const SpatialVolume& correlation,
                                        const Eigen::Vector3i& peak, int radius);

} // namespace pcl_phaser
