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

/** \brief Up to \a count grid peaks in decreasing order of C, in the upper half of the
 *  value range, that are local maxima of their 3x3x3 neighborhood and lie more than \a
 * min_separation radians from every peak already taken (ties by lowest flat index:
 * deterministic). \param[in] grid the correlation on the Euler grid \param[in] count
 * how many peaks at most \param[in] min_separation geodesic distance between distinct
 * peaks, in radians \param[in] num_threads worker threads (the result does not
 * depend on them) */
std::vector<So3GridIndex> distinctPeaks(const So3CorrelationGrid& grid, int count,
                                        double min_separation, int num_threads = 1);

/** \brief A Gaussian on translations, in meters. */
struct TranslationGaussian {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

/** \brief Weighted Gaussian over the (2r+1)^3 lags around the integer peak of a spatial
 *  correlation (paper eq. 15). Weights are the correlation above the lowest value of
 * the block, normalized to sum 1, so they describe the shape of the peak rather than
 * the size of the window; lags wrap around. The mean is relative to the lag-0 shift of
 * the volume (its origin), in meters, like SpatialCorrelationResult::shift. \param[in]
 * correlation a volume from correlateSpectra \param[in] peak integer peak index
 *  \param[in] radius r >= 1 */
TranslationGaussian translationGaussian(const SpatialVolume& correlation,
                                        const Eigen::Vector3i& peak, int radius);

/** \brief Sidelobe statistics of a 3-D correlation around its peak, per axis: the
 *  variances of the central first difference c[i+1] - c[i-1] and of the second
 *  difference c[i-1] - 2 c[i] + c[i+1] over the lags of the box of half width
 *  kSidelobeOuterRadius around the peak, outside the box of half width
 *  kSidelobeInnerRadius (lags wrap around). They measure how strongly the correlation
 *  of these two clouds fluctuates where it carries no match. */
struct CorrelationSidelobes {
  Eigen::Vector3d first_difference_variance = Eigen::Vector3d::Zero();
  Eigen::Vector3d second_difference_variance = Eigen::Vector3d::Zero();
};

/** \brief Half widths (voxels) of the shell whose lags CorrelationSidelobes describes.
 */
constexpr int kSidelobeInnerRadius = 4;
constexpr int kSidelobeOuterRadius = 16;

/** \brief The sidelobe statistics of \a correlation around \a peak (see
 *  CorrelationSidelobes). */
CorrelationSidelobes correlationSidelobes(const SpatialVolume& correlation,
                                          const Eigen::Vector3i& peak);

/** \brief Covariance (m^2) of the sub-voxel peak of findSpatialPeak (kGaussian: on each
 * axis the vertex o of the parabola through the logs of the peak and its two
 * neighbors, or through the raw values where a log is not usable) when the values
 * carry noise whose first and second differences have the variances in \a noise.
 *
 * First-order error propagation. With fitted values (a, b, d) and curvature
 * k = a - 2b + d < 0, the vertex is o = (a - d) / (2k) and
 * do = alpha da + beta db + gamma dd, alpha = (1 - 2o) / (2k), gamma = -(1 + 2o) / (2k)
 * (times 1/a and 1/d in the log domain). Taking beta = -(alpha + gamma), so that o
 * depends on differences only, do = (alpha - gamma) u / 2 + (alpha + gamma) s / 2 with
 * u = da - dd and s = da - 2 db + dd, uncorrelated for stationary noise:
 * var(o) = (alpha - gamma)^2 var(u) / 4 + (alpha + gamma)^2 var(s) / 4.
 * Axes are independent. An axis without a maximum (k >= 0) gets the variance of a
 * uniform error over one voxel, 1/12 voxel^2.
 * \param[in] correlation a volume from correlateSpectra
 * \param[in] peak its integer argmax
 * \param[in] noise variances of the differences of the noise on the values */
Eigen::Matrix3d subVoxelPeakCovariance(const SpatialVolume& correlation,
                                       const Eigen::Vector3i& peak,
                                       const CorrelationSidelobes& noise);

/** \brief Model error (m^2) of the sub-voxel interpolation: per axis the squared
 *  difference between the Gaussian (log-parabola) vertex that findSpatialPeak uses and
 *  the plain parabola vertex through the same three values. Both are exact for their
 *  own peak shape; how far they disagree shows how far the real peak is from either,
 *  i.e. the size of the interpolation bias that noise propagation does not see. Zero
 *  on axes where only one of them applies. Diagonal.
 *  \param[in] correlation a volume from correlateSpectra
 *  \param[in] peak its integer argmax */
Eigen::Matrix3d interpolationModelCovariance(const SpatialVolume& correlation,
                                             const Eigen::Vector3i& peak);

/** \brief Covariance (m^2) of the translation found at the peak of \a correlation =
 *  f * g. The target f at the estimate is modeled as a scaled source plus a mismatch
 *  m, f = alpha g + m; least squares gives 1 - rho^2 = |m|^2 / |f|^2 with rho =
 *  c_peak / (|f| |g|). The mismatch perturbs the correlation by m * g, which fluctuates
 *  like the correlation of unrelated signals, i.e. like the sidelobes of c, scaled by
 *  the mismatch fraction 1 - rho^2 (kept >= 1e-6). That noise is propagated through the
 *  sub-voxel estimate (subVoxelPeakCovariance), and the interpolation model error
 *  (interpolationModelCovariance) is added. No fitted constant. The result is symmetric
 *  positive definite (diagonal, every variance >= 1e-12 voxel^2).
 *  \param[in] correlation a volume from correlateSpectra
 *  \param[in] peak its integer argmax
 *  \param[in] energy_product |f|^2 |g|^2 of the two correlated volumes (see
 *  spectrumEnergy), > 0 */
Eigen::Matrix3d translationCovariance(const SpatialVolume& correlation,
                                      const Eigen::Vector3i& peak,
                                      double energy_product);

/** \brief Sum of the squared voxel values of the volume whose half-spectrum this is
 *  (Parseval: sum over the full spectrum of |F_k|^2 / N). */
double spectrumEnergy(const SpatialSpectrum& spectrum);

/** \brief Standard deviation (radians, per axis) of the model error of a rotation
 *  estimated at bandwidth B, kRotationModelErrorScale * pi / B: a band-limited
 *  correlation cannot tell rotations apart much below its grid spacing pi / B when the
 *  two clouds differ by more than noise (parallax, occlusion, sampling), so the refined
 *  maximum carries a bias of that order that the width of the peak does not show.
 *  The scale 0.11 was fitted on simulated pairs only (89 converged registrations of
 *  makeDemoPair seeds 1-100 at B = 32, 64, 128, `pcl_phaser_covariance_calibration`):
 *  it makes the mean rotation NEES there 3.1 (0.113 gives 3.0). The real scans of the
 *  NEES study were not used. */
constexpr double kRotationModelErrorScale = 0.11;
double rotationModelError(int bandwidth);

/** \brief Covariance (rad^2) of the rotation-vector error omega = Log(R_true
 *  R_est^T): the spread of the correlation peak (the Bingham's tangent covariance in
 * the fixed frame) plus an isotropic model error rotationModelError(bandwidth)^2 I.
 *  Symmetric positive definite. \param[in] peak the Bingham of the peak
 *  \param[in] bandwidth the bandwidth of the correlation */
Eigen::Matrix3d rotationCovariance(const BinghamDistribution& peak, int bandwidth);

} // namespace pcl::phaser
