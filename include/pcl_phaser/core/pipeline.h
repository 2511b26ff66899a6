/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/core/bingham.h>
#include <pcl_phaser/core/parameters.h>
#include <pcl_phaser/core/types.h>

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

/** \brief The registration engine: Eigen and FFTW only, no PCL. align() is its entry
 *  point; pcl::PhaserRegistration translates PCL types into its inputs and its result
 *  back. Layers and data flow: doc/architecture.md. */
namespace pcl::phaser {

/** \brief One hypothesis of the first global search, taken through the translation
 *  stage and verified. */
struct RotationHypothesis {
  /** \brief Its pose in the caller's frames: maps source points into the target frame,
   *  the guess included. */
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();
  /** \brief Its grid rotation and translation in centered coordinates (each cloud
   *  relative to its projection center, the source moved by the guess). */
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double rotation_score = 0.0;   ///< normalized correlation at its grid peak, [-1, 1]
  double overlap = 0.0;          ///< peak of its 3-D correlation (larger is better)
  bool from_orientation = false; ///< a peak of the orientation histograms, not of range
  double inlier_fraction = 0.0;  ///< as PhaserResult::inlier_fraction, for this pose
  double verification_score = 0.0;   ///< as PhaserResult::verification_score
  double free_space_violation = 0.0; ///< as PhaserResult::free_space_violation
  /** \brief As PhaserResult::reverse_free_space_violation, for this pose. */
  double reverse_free_space_violation = 0.0;
  double verification_rank = 0.0; ///< as PhaserResult::verification_rank, for this pose
};

/** \brief What one align() found. On failure (error not empty) transformation is the
 *  guess, converged is false and the other fields keep their defaults. */
struct PhaserResult {
  std::string error; ///< empty on success, else why nothing was estimated
  /** \brief Maps source points into the target frame (p_target = T p_source), the guess
   *  composed: T = [R, c_t + t - R c_s] * guess. */
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();
  /** \brief The final pose verified and, about centroids, its translation peak is
   *  distinct (PhaserParameters::min_peak_score, min_normalized_overlap). */
  bool converged = false;
  /** \brief The center used: the requested one, or what Automatic chose. */
  ProjectionCenter projection_center = ProjectionCenter::SensorOrigin;
  /** \brief The estimate in centered coordinates: q_t ~ rotation q_s + translation for
   *  source and target points relative to their projection centers (c_s, c_t). */
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  /** \brief rotation * c_s, meters: how far a rotation error moves the translation. */
  Eigen::Vector3d lever_arm = Eigen::Vector3d::Zero();
  double rotation_score = 0.0; ///< normalized SO(3) correlation at rotation, [-1, 1]
  /** \brief Peak-to-sidelobe ratio of the Laplacian of the final 3-D correlation, >= 0
   *  (compared with PhaserParameters::min_peak_score about centroids). */
  double translation_score = 0.0;
  /** \brief Peak of the final 3-D correlation over the norms of the two voxel grids:
   *  the cosine similarity of the aligned grids, in [-1, 1] (1: identical). */
  double normalized_overlap = 0.0;
  std::vector<RotationHypothesis> hypotheses; ///< pass-1 hypotheses, in peak order
  int chosen_hypothesis = 0; ///< index of the one the estimate was refined from
  int passes = 0;            ///< passes run
  /** \brief Verification of the final pose (source samples on a grid of
   *  verification_radius against the target points within that radius): the share of
   *  samples with an agreeing target point within the radius, in [0, 1]. */
  double inlier_fraction = 0.0;
  double verification_score = 0.0;   ///< the share weighted by closeness, in [0, 1]
  double free_space_violation = 0.0; ///< share in space the target saw through, [0, 1]
  /** \brief Share of target samples in space the source saw through, [0, 1]. */
  double reverse_free_space_violation = 0.0;
  /** \brief The order of poses where verification ranks them (about sensor origins):
   *  verification_score less 6 x the sum of both free-space violations, in [-12, 1];
   *  among poses within the verification limits, and among those outside them (first
   *  those with at least half the inlier share of the best-matching hypothesis), the
   *  higher wins. */
  double verification_rank = 0.0;
  /** \brief The highest verification_rank among the pass-1 hypotheses distinct from the
   *  final pose (turned from it by more than 10 deg, or moved by more than two coarse
   *  voxels: farther than a polish climbs), or -infinity when there is none. About
   *  sensor origins, verified needs verification_rank above it by more than 2.33
   *  runner_up_error: when a distinct pose has about as much evidence (a symmetric
   *  yard, a repeated facade, a narrow view), the scene admits both. */
  double runner_up_rank = -std::numeric_limits<double>::infinity();
  /** \brief Standard error of verification_rank - runner_up_rank from the samples'
   *  paired differences under the two poses (0 without a runner-up, and about
   * centroids). About sensor origins, verified needs the difference above 2.33 times it
   * (one-sided 99 %): a small source (a narrow view, a few hundred samples) matched
   * about as well by a distinct pose is not told apart by the choice of samples. */
  double runner_up_error = 0.0;
  /** \brief How well the matched samples pin the translation down in every direction:
   *  the smallest eigenvalue of sum w n n^T over the inliers with a normal, over the
   *  total weight, in [0, 1/3]; near 0 when a direction is left free (the ground
   *  alone, walls of one direction); 0 without normals. */
  double constraint = 0.0;
  double verification_radius = 0.0; ///< meters: half the coarse voxel
  int verification_samples = 0;     ///< source samples verified
  /** \brief Enough samples and, about sensor origins, inlier_fraction, constraint
   *  and both free-space violations within PhaserParameters' limits and
   *  verification_rank above runner_up_rank by more than 2.33 runner_up_error. */
  bool verified = false;
  /** \brief Grid rotations around the last rotation peak, moved onto rotation
   *  (quaternions w, x, y, z), and their weights (correlation above the block's
   *  lowest); see rotationUncertainty(). */
  std::vector<Eigen::Vector4d> rotation_samples;
  std::vector<double> rotation_weights;
  /** \brief Covariance of the translation, m^2 (target frame): the error of the
   *  sub-voxel peak of the last 3-D correlation under the noise its sidelobes and
   *  mismatch imply, not the width of the peak. */
  Eigen::Matrix3d translation_covariance = Eigen::Matrix3d::Zero();
  /** \brief Covariance of the final pose from its own geometric evidence
   *  (fitCovariance: the point-to-plane fit of the verification samples, a sandwich
   *  over blocks of correlated samples, with a model-error factor), 6 x 6, ordered
   *  and in the caller's frames as poseCovariance; zero when fewer than
   *  kMinFitSamples samples match or the matches leave a direction unmeasured. */
  Eigen::Matrix<double, 6, 6> fit_covariance = Eigen::Matrix<double, 6, 6>::Zero();
  double target_ms = 0.0;       ///< ms, the target's preparation; 0 from the cache
  double sampling_ms = 0.0;     ///< ms, spherical binning of the source
  double sht_ms = 0.0;          ///< ms, spherical harmonic transforms of the source
  double so3_ms = 0.0;          ///< ms, SO(3) correlations and peak searches
  double refinement_ms = 0.0;   ///< ms, Newton refinement of the rotation
  double translation_ms = 0.0;  ///< ms, voxelization, 3-D FFTs, correlation, peaks
  double verification_ms = 0.0; ///< ms, source samples and pose verification
  double orientation_ms = 0.0;  ///< ms, surface patches and orientation histograms
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

/** \brief Bingham distribution of the rotation (orientation M, concentrations Z, mode
 *  = the estimate), fitted to \a result's rotation samples (paper eqs. 6, 7, 11, 12);
 *  uniform when there are none. The spread is expressed in the target frame. */
BinghamDistribution rotationUncertainty(const PhaserResult& result);

/** \brief 6 x 6 covariance of the pose error, ordered (rotation vector [rad],
 *  translation [m]) for omega = Log(R_true R_est^T) and nu = t_true - t_est of
 *  PhaserResult::transformation, so its inverse can serve as the information matrix of
 *  a pose-graph edge. It is result.fit_covariance: the spread of the final pose's own
 *  point-to-plane fit on the verification samples (fitCovariance: a sandwich over
 *  blocks of correlated samples, times a model-error factor fitted on real revisits),
 *  calibrated on revisits of lidar/balm_handheld (doc/method.md section 8). When the
 *  fit cannot give one (fewer than kMinFitSamples matched samples, a direction left
 *  unmeasured), the spectral model: the Bingham's tangent covariance plus a model
 *  error per axis, and the translation covariance plus the rotation error through the
 *  lever arm. Symmetric positive definite when \a result converged; zero otherwise.
 *  \param[in] rotation rotationUncertainty(result), for the spectral model
 *  \param[in] bandwidth the bandwidth the result was computed with, for the spectral
 *  model */
Eigen::Matrix<double, 6, 6> poseCovariance(const PhaserResult& result,
                                           const BinghamDistribution& rotation,
                                           int bandwidth);

} // namespace pcl::phaser
