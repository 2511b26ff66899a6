/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "so3/so3_correlation.h"
#include "spatial/spatial_correlation.h"

#include <pcl_phaser/core/bingham.h>

#include <Eigen/Core>

#include <vector>

namespace pcl::phaser {

/** \brief A rotation of the SO(3) grid and the correlation there. */
struct RotationSample {
  Eigen::Matrix3d rotation;
  double value;
};

/** \brief The (2r+1)^3 block of grid samples around \a peak, a true 3-D neighborhood:
 *  alpha and gamma wrap modulo N, and a beta index beyond the poles reflects, because
 *  Rz(a) Ry(-b) Rz(c) = Rz(a + pi) Ry(b) Rz(c - pi): index j < 0 reads row -1 - j and
 *  j >= N reads row 2N - 1 - j, both at (a + Bo, c - Bo). Near the poles several
 *  samples may be (almost) the same rotation; they are kept, each with its value.
 *  \param[in] grid the correlation on the Euler grid
 *  \param[in] peak center of the block
 *  \param[in] radius r >= 0 */
std::vector<RotationSample> rotationNeighborhood(const So3CorrelationGrid& grid,
                                                 const So3GridIndex& peak, int radius);

/** \brief Up to \a count grid peaks, best first (ties: lowest flat index): samples in
 *  the upper half of the value range that are maxima of their 3x3x3 block and lie more
 *  than \a min_separation radians from every peak taken. The result does not depend
 *  on \a num_threads. On a grid limited in tilt (So3CorrelationGrid::betaRows) only
 *  the rows whose beta neighbors were computed are searched, the range over them. */
std::vector<So3GridIndex> distinctPeaks(const So3CorrelationGrid& grid, int count,
                                        double min_separation, int num_threads = 1);

/** \brief How strongly a 3-D correlation fluctuates where it carries no match: per axis
 *  the variances of the central first difference c[i+1] - c[i-1] and of the second
 *  difference c[i-1] - 2 c[i] + c[i+1] over the wrapped lags within
 *  kSidelobeOuterRadius of the peak but not within kSidelobeInnerRadius. */
struct CorrelationSidelobes {
  Eigen::Vector3d first_difference_variance = Eigen::Vector3d::Zero();
  Eigen::Vector3d second_difference_variance = Eigen::Vector3d::Zero();
};

/** \brief Half widths (voxels) of the shell of lags CorrelationSidelobes describes. */
constexpr int kSidelobeInnerRadius = 4;
constexpr int kSidelobeOuterRadius = 16;

CorrelationSidelobes correlationSidelobes(const SpatialVolume& correlation,
                                          const Eigen::Vector3i& peak);

/** \brief Covariance (m^2, diagonal) of findSpatialPeak's kGaussian sub-voxel vertex
 *  when the values carry noise with the difference variances \a noise, by first-order
 *  propagation. Per axis, with fitted values (a, b, d) (logs, or raw values where a log
 *  is unusable) and k = a - 2b + d < 0, the vertex o = (a - d) / (2k) moves by
 *  alpha da + beta db + gamma dd, alpha = (1 - 2o) / (2k), gamma = -(1 + 2o) / (2k)
 *  (times 1/a, 1/d for logs), beta = -(alpha + gamma); so var(o) = (alpha - gamma)^2
 *  var(u) / 4 + (alpha + gamma)^2 var(s) / 4 with u, s the first and second
 *  differences. An axis without a maximum gets 1/12 voxel^2 (uniform over a voxel). */
Eigen::Matrix3d subVoxelPeakCovariance(const SpatialVolume& correlation,
                                       const Eigen::Vector3i& peak,
                                       const CorrelationSidelobes& noise);

/** \brief Model error (m^2, diagonal) of the sub-voxel interpolation: per axis the
 *  squared difference of the Gaussian (log-parabola) and plain parabola vertices
 *  through the same three values, a measure of the bias noise propagation does not
 *  see; zero where only one applies. */
Eigen::Matrix3d interpolationModelCovariance(const SpatialVolume& correlation,
                                             const Eigen::Vector3i& peak);

/** \brief Covariance (m^2) of the translation at the integer \a peak of \a correlation
 *  = f * g. Modeling f = alpha g + m, the mismatch fraction 1 - rho^2 = |m|^2 / |f|^2
 *  (rho = c_peak / (|f| |g|), kept >= 1e-6) scales the sidelobe fluctuation into the
 *  noise m * g puts on c; that noise is propagated (subVoxelPeakCovariance) and the
 *  interpolation model error added. No fitted constant; diagonal, every variance >=
 *  1e-12 voxel^2. \param[in] energy_product |f|^2 |g|^2 (spectrumEnergy), > 0 */
Eigen::Matrix3d translationCovariance(const SpatialVolume& correlation,
                                      const Eigen::Vector3i& peak,
                                      double energy_product);

/** \brief Sum of the squared voxel values of the volume whose half-spectrum this is. */
double spectrumEnergy(const SpatialSpectrum& spectrum);

/** \brief Standard deviation (radians, per axis) of the model error of a rotation
 *  estimated at bandwidth B, kRotationModelErrorScale pi / B: where two clouds differ
 *  by more than noise, a band-limited correlation cannot tell rotations apart much
 *  below its grid spacing pi / B. The scale was fitted on simulated pairs (makeDemoPair
 *  seeds 1-100, B = 32, 64, 128) to a mean rotation NEES of 3. */
constexpr double kRotationModelErrorScale = 0.11;
double rotationModelError(int bandwidth);

/** \brief Covariance (rad^2) of the rotation-vector error Log(R_true R_est^T): the
 *  Bingham peak's tangent covariance in the fixed frame plus rotationModelError(B)^2 I.
 */
Eigen::Matrix3d rotationCovariance(const BinghamDistribution& peak, int bandwidth);

} // namespace pcl::phaser
