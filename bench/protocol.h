/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The evaluation protocol of doc/benchmarks.md: random large poses with exact truth,
 * the paper's perturbations (noise by PSNR, random sparsification, partial overlap),
 * and the error measures (RRE, RTE).
 */
#pragma once

#include "statistics.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>

#include <cmath>
#include <random>
#include <string>

namespace pcl::phaser {
namespace bench {

using PointT = pcl::PointXYZI;
using Cloud = pcl::PointCloud<PointT>;

/** \brief Rotation error in degrees: the angle of R_est^T R_true. */
double rreDeg(const Eigen::Matrix4d& estimate, const Eigen::Matrix4d& truth);

/** \brief Translation error in meters: |t_est - t_true|. */
double rteM(const Eigen::Matrix4d& estimate, const Eigen::Matrix4d& truth);

/** \brief A uniform random rotation (normalized Gaussian quaternion) and a translation
 * uniform in the ball of radius \a t_max. Below pi, \a max_tilt (radians) restricts the
 * rotation to a uniform yaw after a tilt uniform on the cap of that angle about z. */
Eigen::Matrix4d randomPose(std::mt19937& rng, double t_max, double max_tilt = M_PI);

/** \brief A perturbation of the source scan before it is moved. */
struct Condition {
  enum class Kind { Clean, Noise, Sparsity, Overlap };
  Kind kind = Kind::Clean;
  /** PSNR in dB (Noise), kept fraction of the points (Sparsity) or of the azimuth
   * circle (Overlap). */
  double value = 0.0;

  /** \brief "clean", "noise", "sparsity", "overlap". */
  std::string sweep() const;
  /** \brief e.g. "PSNR 50 dB", "keep 25 %", "overlap 10 %". */
  std::string label() const;
};

/** \brief Parses "clean", "noise:50", "sparsity:0.25", "overlap:0.1".
 * \return false on a malformed text or a value out of range */
bool parseCondition(const std::string& text, Condition& condition);

/** \brief Applies \a condition to \a cloud in place.
 *  - Noise: zero-mean Gaussian noise on x, y, z with sigma = r_max / 10^(PSNR/20),
 *    r_max the largest range from the origin, and on intensity with sigma = i_max /
 *    10^(PSNR/20), i_max the largest intensity (the paper's protocol).
 *  - Sparsity: keeps each point with probability \a value.
 *  - Overlap: keeps the points whose azimuth about the origin lies in a sector of
 *    \a value x 360 deg centered on a random direction (what a sensor with a narrower
 *    horizontal field of view would have seen).
 * The cloud stays dense (non-finite points are expected to have been removed). */
void applyCondition(const Condition& condition, Cloud& cloud, std::mt19937& rng);

/** \brief Keeps the points of \a cloud whose azimuth about the origin lies within
 *  \a half_width of \a center (radians): the Overlap condition about a given direction.
 */
void keepSector(Cloud& cloud, double center, double half_width);

// median() and quantile() (NaN when empty): statistics.h, shared with the tools.
using pcl::phaser::median;
using pcl::phaser::quantile;

} // namespace bench
} // namespace pcl::phaser
