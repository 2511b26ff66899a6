/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/core/cloud_signals.h>

#include <Eigen/Core>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

/** \brief The registration engine: Eigen and FFTW only, no PCL (spherical sampling and
 *  harmonic transform, SO(3) correlation and refinement, 3-D spatial correlation,
 *  channel fusion, Bingham and Gaussian uncertainty). prepareTarget() and
 *  estimateTransform() are its entry points; pcl::PhaserRegistration wraps them. */
namespace pcl_phaser {

/** \brief Parameters of one registration, with the defaults PhaserRegistration uses. */
struct PhaserParameters {
  int bandwidth = 64;            ///< spherical bandwidth B, 1..256
  int spatial_grid_size = 128;   ///< voxels along the longest axis, 8..1024
  double voxel_size = 0.0;       ///< explicit voxel size in metres; 0 = from grid size
  int refinement_iterations = 2; ///< Newton iterations on SO(3) (per stage), 0..10
  int fusion_levels = 5;       ///< Laplacian pyramid levels of the channel fusion, 1..8
  int rotation_candidates = 3; ///< distinct SO(3) peaks tried in pass 1, 1..10
  int passes = 3; ///< at most; 1: one global pass; 2+: re-project, re-correlate
  /** \brief Worker threads, 0..64; 0 (default): one per hardware thread
   *  (omp_get_num_procs, at most 64), PCL's convention. Results are bit-identical for
   *  any count. */
  int num_threads = 0;
  /** \brief After the Newton refinement of plain C, refine again on the
   *  energy-normalised correlation (refineRotation with supports), within
   *  normalizedRefinementRadius(B) of the plain maximum. It removes most of the
   *  pull of the field-of-view edges towards equal sensor tilt (simulated tilted-sensor
   *  pairs: median 1.13 -> 0.56 deg) for a few ms more per align (doc/benchmarks.md
   *  section 6). */
  bool normalized_refinement = true;
  /** \brief Rotation hypotheses from the surface-orientation histograms
   *  (orientationSpectrum), tried beside the range peaks, 0..10 (0: none). The
   *  histogram does not move with the sensor, so it finds the rotation of scans taken
   *  metres apart, where the range function's parallax misleads. */
  int orientation_candidates = 6;
  /** \brief Bandwidth of the orientation histograms, 8..128. */
  int orientation_bandwidth = 32;
  /** \brief Exponent of the cross-power whitening of the global translation search
   *  (correlateSpectraWhitened), in [0, 1]. Later passes search a residual on the
   *  fine grid without it: there the pull of the overlap hill towards zero residual
   *  is a pull towards the current estimate. */
  double whitening = 0.5;
  /** \brief Clouds are seen from their sensor origins (the projection centre). Then
   *  hypotheses are ranked by verifyPose, including the samples in space the target saw
   *  through, and the orientation histograms add hypotheses. Otherwise (object scans
   *  about their centroids) hypotheses are ranked by their occupancy correlation peak
   *  and only the range peaks are tried. */
  bool sensor_centred = true;
  /** \brief A pose is verified when at least this (weighted) share of the source
   *  samples has a target point within the verification radius whose normal agrees,
   *  in [0, 1] (doc/benchmarks.md section 9 has the measured distributions). */
  double min_inlier_fraction = 0.2;
  /** \brief ... and, with sensor_centred, at most this share of them lies in space
   *  the target saw through, in [0, 1]. */
  double max_free_space_violation = 0.02;
  /** \brief ... and its matched samples pin the translation down in every direction:
   *  PoseVerification::constraint at least this, in [0, 1/3]. */
  double min_constraint = 0.04;
};

/** \brief Fewest verification samples (occupied cells of the verification radius) a
 *  source needs for its pose to be verified: fewer cannot tell a pose from another. */
constexpr int kMinVerificationSamples = 20;

/** \brief How far (radians, at B = 64; scaled by 64 / B, like the precision of the
 *  plain maximum) the normalised refinement may move the rotation from the maximum of
 *  plain C. The tilt pull it corrects is about 40 % of the relative tilt of the two
 *  sensors, so about 1 deg for vehicles; unbounded, the normalised objective
 *  can also climb away from a maximum whose viewpoint has not settled, towards a
 *  smaller overlap that matches better (demo seed 4: 1.3 -> 4.9 deg), and on sparse
 *  scans it is noisier than plain C. Radius 0.5 / 0.75 / 1 deg: makeDemoPair seeds 1-40
 *  median RRE 0.73 / 0.56 / 0.42 deg (plain 1.13); the 102 real-scan poses of the NEES
 *  study RMS RRE 0.32 / 0.36 / 0.38 deg (plain 0.43), inside the 95 % ellipsoid 81 / 80
 *  / 79 % (plain 90 %, doc/benchmarks.md section 5). */
constexpr double kNormalizedRefinementRadius = 0.75 * M_PI / 180.0;

/** \brief The trust radius (radians) at bandwidth B: kNormalizedRefinementRadius * 64 /
 * B.
 */
inline double normalizedRefinementRadius(int bandwidth)
{
  return kNormalizedRefinementRadius * 64.0 / bandwidth;
}

/** \brief The worker threads \a num_threads stands for: itself, or for 0 one per
 *  hardware thread (at most 64). */
int resolveThreadCount(int num_threads);

/** \brief Empty when \a p is legal, else the reason (for PCL_ERROR). */
std::string validateParameters(const PhaserParameters& p);

/** \brief One distinct peak of the first global rotation search, taken through the
 *  translation stage. */
struct RotationHypothesis {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity(); ///< grid rotation
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  ///< its translation
  double rotation_score = 0.0;   ///< normalised C at the grid peak
  double overlap = 0.0;          ///< peak of the 3-D correlation: how well it overlaps
  bool from_orientation = false; ///< a peak of the orientation histograms, not of range
  double inlier_fraction = 0.0;  ///< PoseVerification::inlier_fraction of the pose
  double verification_score = 0.0;   ///< PoseVerification::score of the pose
  double free_space_violation = 0.0; ///< PoseVerification::free_space_violation
};

/** \brief What one registration found, in centred coordinates: for source points q_s
 * and target points q_t (each relative to its projection centre), q_t ~ R q_s + t. */
struct PhaserEstimate {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double rotation_score = 0.0;    ///< C(R) / (|f| |h|), in [-1, 1]
  double translation_score = 0.0; ///< peak-to-sidelobe ratio of the 3-D correlation
  /** \brief Peak of the final 3-D correlation over the norms of the two voxel grids:
   *  the cosine similarity of the aligned grids, in [-1, 1] (1: identical). */
  double normalized_overlap = 0.0;
  double sampling_ms = 0.0;    ///< spherical binning of the source
  double sht_ms = 0.0;         ///< spherical harmonic transform of the source
  double so3_ms = 0.0;         ///< SO(3) correlation and peak search
  double refinement_ms = 0.0;  ///< Newton refinement of the rotation
  double translation_ms = 0.0; ///< voxelisation, 3-D FFT, correlation, peak
  double target_ms = 0.0;      ///< target preparation (0 when it came from the cache)
  int passes = 0;              ///< passes run
  std::vector<RotationHypothesis> hypotheses; ///< pass-1 candidates, in peak order
  int chosen_hypothesis = 0; ///< the one with the best verification score
  /** \brief Verification of the final pose (verifyPose): source samples on a grid of
   *  verification_radius against the target points within that radius. */
  double inlier_fraction = 0.0;
  double verification_score = 0.0;
  double free_space_violation = 0.0;
  double constraint = 0.0;          ///< PoseVerification::constraint of the final pose
  double verification_radius = 0.0; ///< metres: half the coarse voxel
  int verification_samples = 0;     ///< source samples verified
  /** \brief The final pose passed verification: enough samples and, with
   *  sensor_centred, inlier_fraction >= min_inlier_fraction, constraint >=
   *  min_constraint and free_space_violation <= max_free_space_violation. About
   *  centroids (object scans, keypoints) the radius of half a coarse voxel is below the
   *  sampling of many clouds, so only the sample count is required there and the
   *  adapter also asks for a distinct correlation peak. */
  bool verified = false;
  double verification_ms = 0.0; ///< source samples and pose verification
  double orientation_ms = 0.0;  ///< surface patches, histogram and its correlation
  /** \brief Grid rotations around the last rotation peak, moved onto the estimate
   *  (quaternions w, x, y, z), and their weights (correlation above the block's
   * lowest). */
  std::vector<Eigen::Vector4d> rotation_samples;
  std::vector<double> rotation_weights;
  /** \brief Covariance of the translation (m^2): the error of the sub-voxel peak of
   *  the last 3-D correlation under the noise its sidelobes and mismatch imply (see
   *  translationCovariance in peak_neighbourhood.h). */
  Eigen::Matrix3d translation_covariance = Eigen::Matrix3d::Zero();
};

/** \brief Everything that depends on the target alone (its spherical spectrum, its
 * voxel grid and voxel spectrum): computed once, reused for many sources. Immutable. */
class TargetModel;

/** \brief Prepares a target.
 *  \param[in] points 3 x n target points relative to the target's projection centre
 *  \param[in] params parameters (bandwidth, grid)
 *  \param[in] channels per-point channel values to fuse (normalised here, per cloud)
 *  \throws InvalidArgument when parameters are illegal or the points carry no signal
 *  (none finite, all at the centre, or all in one direction) */
std::shared_ptr<const TargetModel> prepareTarget(const Eigen::Matrix3Xd& points,
                                                 const PhaserParameters& params,
                                                 const ChannelValues& channels = {});

/** \brief Time spent preparing \a model, in milliseconds. */
double preparationTime(const TargetModel& model);

/** \brief Registers a source against a prepared target.
 *  \param[in] target prepared with the same bandwidth and grid parameters
 *  \param[in] points 3 x n source points relative to the source's projection centre
 *  \param[in] params parameters
 *  \param[in] channels the same channels as the target's (normalised here, per cloud)
 *  \throws InvalidArgument when parameters are illegal, do not match the target model,
 * or the source carries no signal */
PhaserEstimate estimateTransform(const TargetModel& target,
                                 const Eigen::Matrix3Xd& points,
                                 const PhaserParameters& params,
                                 const ChannelValues& channels = {});

} // namespace pcl_phaser
