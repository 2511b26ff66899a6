/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/core/bingham.h>
#include <pcl_phaser/core/parameters.h>
#include <pcl_phaser/core/result.h>
#include <pcl_phaser/core/types.h>

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <string>
#include <vector>

/** \brief The registration engine (Eigen and FFTW, no PCL); entry point align(). */
namespace pcl::phaser {

/** \brief The source of one align(): finite points (3 x n) and channel values. */
struct SourceCloud {
  Eigen::Matrix3Xd points;
  ChannelValues channels;
};

/** \brief The target of any number of (concurrent) align() calls: caches its spectra
 *  per projection center and parameters. */
class Target {
public:
  /** \param[in] points 3 x n finite points in the target frame
   *  \param[in] channels per-point channel values (may be empty) */
  explicit Target(Eigen::Matrix3Xd points, ChannelValues channels = {});
  ~Target();
  Target(const Target&) = delete;
  Target& operator=(const Target&) = delete;

  const Eigen::Matrix3Xd& points() const { return points_; } ///< as constructed

private:
  friend class TargetAccess;
  Eigen::Matrix3Xd points_;
  ChannelValues channels_;
  struct Cache;
  std::unique_ptr<Cache> cache_;
};

/** \brief Registers \a source against \a target. Never throws for bad input (illegal
 *  parameters, no finite points, coordinates beyond 1e6 m, a non-finite guess, no
 *  spherical signal): the result's error says why.
 *  \param[in] target the target, prepared once for many sources
 *  \param[in] source the source points and channels, in the source frame
 *  \param[in] guess applied to the source first; the estimate is composed with it
 *  \param[in] params the settings */
PhaserResult align(const Target& target, const SourceCloud& source,
                   const Eigen::Matrix4d& guess, const PhaserParameters& params);

/** \brief Bingham distribution of the rotation (mode = the estimate), fitted to
 *  \a result's rotation samples (paper eqs. 6, 7, 11, 12), in the target frame;
 *  uniform when there are none. */
BinghamDistribution rotationUncertainty(const PhaserResult& result);

/** \brief 6 x 6 covariance of the pose error, ordered (rotation vector [rad],
 *  translation [m]) for omega = Log(R_true R_est^T), nu = t_true - t_est (the inverse
 *  of a pose-graph edge's information): result.fit_covariance, else a spectral model.
 *  Symmetric positive definite when \a result converged; zero otherwise.
 *  \param[in] rotation rotationUncertainty(result), for the spectral model
 *  \param[in] bandwidth the bandwidth of the result, for the spectral model */
Eigen::Matrix<double, 6, 6> poseCovariance(const PhaserResult& result,
                                           const BinghamDistribution& rotation,
                                           int bandwidth);

} // namespace pcl::phaser
