/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/core/bingham.h>
#include <pcl_phaser/core/parameters.h>
#include <pcl_phaser/core/types.h>

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <string>
#include <vector>

/** \brief The registration engine: Eigen and FFTW only, no PCL. align() is its entry
 *  point; pcl::PhaserRegistration translates PCL types into its inputs and its result
 *  back. Layers and data flow: doc/architecture.md. */
namespace pcl::phaser {

/** \brief Milliseconds spent in each stage of one align(). */
struct StageTimes {
  double target = 0.0;       ///< the target's preparation; 0 from the cache
  double sampling = 0.0;     ///< spherical binning of the source
  double sht = 0.0;          ///< spherical harmonic transforms of the source
  double so3 = 0.0;          ///< SO(3) correlations and peak searches
  double refinement = 0.0;   ///< Newton refinement of the rotation
  double translation = 0.0;  ///< voxelization, 3-D FFTs, correlation, peaks
  double verification = 0.0; ///< source samples and pose verification
  double orientation = 0.0;  ///< surface patches and orientation histograms
  /** \brief The sum of the stages. */
  double total() const
  {
    return target + sampling + sht + so3 + refinement + translation + orientation +
           verification;
  }
};

/** \brief How a pose verifies: source samples (one per cell of the verification
 *  radius) against the target points within that radius. Shares are in [0, 1]. */
struct Verification {
  double inlier_fraction = 0.0;      ///< share with a target point within the radius
  double score = 0.0;                ///< the share weighted by closeness, [0, 1]
  double free_space_violation = 0.0; ///< share where the target's sensor saw through
  /** \brief Share of target samples where the source's sensor saw through, [0, 1]. */
  double reverse_free_space_violation = 0.0;
  /** \brief How well the matched samples pin the translation down in every direction:
   *  the smallest eigenvalue of sum w n n^T over the inliers with a normal, over the
   *  total weight, [0, 1/3]; near 0 when a direction is left free (the ground alone,
   *  walls of one direction); 0 without normals. */
  double constraint = 0.0;
  /** \brief The order in which verification ranks poses (about sensor origins): score
   *  less 6 x the sum of both free-space violations, [-12, 1]. */
  double rank = 0.0;
};

/** \brief A hypothesis of the global search, taken through the translation search and
 *  verified. */
struct Hypothesis {
  /** \brief Its pose in the caller's frames: maps source points into the target frame,
   *  the guess included. */
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();
  /** \brief Its rotation and translation in centered coordinates (each cloud relative
   *  to its projection center, the source moved by the guess). */
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double rotation_score = 0.0;   ///< normalized correlation at its grid peak, [-1, 1]
  double overlap = 0.0;          ///< peak of its 3-D correlation (larger is better)
  bool from_orientation = false; ///< a peak of the orientation histograms, not of range
  Verification verification;     ///< of this pose
};

/** \brief What one align() measured on the way to its answer (failed: defaults). */
struct PhaserDiagnostics {
  double rotation_score = 0.0; ///< normalized SO(3) correlation at the estimate
  /** \brief Peak-to-sidelobe ratio of the Laplacian of the final 3-D correlation, >= 0
   *  (compared with PhaserParameters::min_peak_score about centroids). */
  double translation_score = 0.0;
  /** \brief Peak of the final 3-D correlation over the norms of the two voxel grids:
   *  the cosine similarity of the aligned grids, [-1, 1]. */
  double normalized_overlap = 0.0;
  Verification verification; ///< of the final pose
  /** \brief The highest rank among the hypotheses distinct from the final pose (turned
   *  by more than 10 deg or moved by more than two coarse voxels); -infinity: none. A
   *  distinct pose with about as much evidence (a symmetric yard, a narrow view) is as
   *  likely, so verified needs the final rank above it by 2.33 runner_up_error. */
  double runner_up_rank = -std::numeric_limits<double>::infinity();
  /** \brief Standard error of the rank difference to the runner-up from the samples'
   *  paired differences (0 without one, and about centroids). */
  double runner_up_error = 0.0;
  double verification_radius = 0.0; ///< meters: half the coarse voxel
  int verification_samples = 0;     ///< source samples verified
  /** \brief Enough samples and, about sensor origins, the verification within
   *  PhaserParameters' limits and the runner-up outranked (runner_up_rank). */
  bool verified = false;
  std::vector<Hypothesis> hypotheses; ///< every hypothesis, pass-1 peaks first
  int passes = 0;                     ///< passes run
  /** \brief Grid rotations around the last rotation peak moved onto the estimate
   *  (quaternions w, x, y, z) and their weights, for rotationUncertainty(). */
  std::vector<Eigen::Vector4d> rotation_samples;
  std::vector<double> rotation_weights;
  StageTimes times;
};

/** \brief What one align() found. On failure (error not empty) transformation is the
 *  guess, converged is false and the rest keeps its defaults. */
struct PhaserResult {
  std::string error; ///< empty on success, else why nothing was estimated
  /** \brief Maps source points into the target frame (p_target = T p_source), the guess
   *  composed: T = [R, c_t + t - R c_s] * guess for the estimate (R, t) between the
   *  clouds centered on their projection centers c_s, c_t. */
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();
  /** \brief The final pose verified and, about centroids, its translation peak is
   *  distinct (PhaserParameters::min_peak_score, min_normalized_overlap). */
  bool converged = false;
  /** \brief The center used: the requested one, or what Automatic chose. */
  ProjectionCenter projection_center = ProjectionCenter::SensorOrigin;
  int chosen_hypothesis = 0; ///< index of the hypothesis the estimate was refined from
  /** \brief R c_s, meters: how far a rotation error moves the translation. */
  Eigen::Vector3d lever_arm = Eigen::Vector3d::Zero();
  /** \brief Covariance of the translation, m^2 (target frame): the error of the last
   *  3-D correlation's sub-voxel peak under the noise its sidelobes imply. */
  Eigen::Matrix3d translation_covariance = Eigen::Matrix3d::Zero();
  /** \brief Covariance of the final pose from its point-to-plane fit on the
   *  verification samples (fitCovariance), ordered and in the caller's frames as
   *  poseCovariance; zero when too few samples match or a direction is unmeasured. */
  Eigen::Matrix<double, 6, 6> fit_covariance = Eigen::Matrix<double, 6, 6>::Zero();
  PhaserDiagnostics diagnostics; ///< scores, verification, hypotheses, timings
};

/** \brief The source of one align(): finite points in the caller's frame (3 x n) and
 *  the values of its channels (the same channels as the target's, any scale). */
struct SourceCloud {
  Eigen::Matrix3Xd points;
  ChannelValues channels;
};

class TargetModel;

/** \brief The target of any number of align() calls: its finite points in its own frame
 *  and its channels, and what align() derives from them alone (spherical and voxel
 *  spectra), built on first use per projection center and parameters and then reused.
 *  Thread-safe: one Target may serve concurrent align() calls. */
class Target {
public:
  /** \param[in] points 3 x n finite points in the target frame
   *  \param[in] channels per-point channel values (may be empty) */
  explicit Target(Eigen::Matrix3Xd points, ChannelValues channels = {});
  ~Target();
  Target(const Target&) = delete;
  Target& operator=(const Target&) = delete;

  /** \brief The points given at construction. */
  const Eigen::Matrix3Xd& points() const { return points_; }

private:
  friend class TargetAccess;
  Eigen::Matrix3Xd points_;
  ChannelValues channels_;
  struct Cache;
  std::unique_ptr<Cache> cache_;
};

/** \brief Registers \a source against \a target: the rotation from the correlation of
 *  their spherical spectra on SO(3), the translation from the correlation of their
 *  voxel grids, every hypothesis verified geometrically. Never throws for bad input:
 *  illegal parameters, no finite points, coordinates beyond 1e6 m, a non-finite guess
 *  or clouds without spherical signal give a result whose error says why.
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
 *  translation [m]) for omega = Log(R_true R_est^T) and nu = t_true - t_est of
 *  PhaserResult::transformation: the inverse of a pose-graph edge's information
 *  matrix. It is result.fit_covariance (calibrated on real revisits) or, when the fit
 *  gave none, the spectral model: the Bingham's tangent covariance plus a model error
 *  per axis, and the translation covariance plus the rotation error through the lever
 *  arm. Symmetric positive definite when \a result converged; zero otherwise.
 *  \param[in] rotation rotationUncertainty(result), for the spectral model
 *  \param[in] bandwidth the bandwidth of the result, for the spectral model */
Eigen::Matrix<double, 6, 6> poseCovariance(const PhaserResult& result,
                                           const BinghamDistribution& rotation,
                                           int bandwidth);

} // namespace pcl::phaser
