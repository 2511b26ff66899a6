/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/core/parameters.h>

#include <Eigen/Core>

#include <limits>
#include <string>
#include <vector>

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
  double total() const       ///< the sum of the stages
  {
    return target + sampling + sht + so3 + refinement + translation + orientation +
           verification;
  }
};

/** \brief How a pose verifies: source samples against the target points within the
 *  verification radius. Shares are in [0, 1]. */
struct Verification {
  double inlier_fraction = 0.0;      ///< share with a target point within the radius
  double score = 0.0;                ///< the share weighted by closeness
  double free_space_violation = 0.0; ///< share where the target's sensor saw through
  double reverse_free_space_violation = 0.0; ///< target samples the source saw through
  /** \brief How well the matches pin the translation in every direction: the smallest
   *  eigenvalue of the inliers' sum w n n^T over the weight of all samples where the
   *  free space is known (sensor viewpoints), else over the inliers' weight (a right
   *  pose of a partial object view matches a third of its samples, and that share has
   *  its own limit), [0, 1/3]; 0 without normals. */
  double constraint = 0.0;
  /** \brief Ranks poses: score less 6 x both free-space violations, [-12, 1]. */
  double rank = 0.0;
};

/** \brief A verified hypothesis of the global search. */
struct Hypothesis {
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity(); ///< as the result's
  /// its rotation and translation about the projection centers
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double rotation_score = 0.0; ///< normalized correlation at its grid peak, [-1, 1]
  double overlap = 0.0;        ///< peak of its 3-D correlation (larger is better)
  /// a peak of a correlation that needs no common center (the orientation histograms,
  /// or the occupancy magnitudes of objects), not of the range images
  bool from_orientation = false;
  Verification verification; ///< of this pose
};

/** \brief What one align() measured on the way to its answer (failed: defaults). */
struct PhaserDiagnostics {
  double rotation_score = 0.0; ///< normalized SO(3) correlation at the estimate
  /** \brief Peak-to-sidelobe ratio of the final 3-D correlation's Laplacian, >= 0. */
  double translation_score = 0.0;
  /** \brief Cosine similarity of the aligned voxel grids, [-1, 1]. */
  double normalized_overlap = 0.0;
  Verification verification; ///< of the final pose
  /** \brief Highest rank of a hypothesis distinct from the final pose (over 10 deg or
   *  two coarse voxels away); -infinity: none. */
  double runner_up_rank = -std::numeric_limits<double>::infinity();
  /** \brief Standard error of the rank gap, samples within kFitBlockVoxels coarse
   *  voxels of each other counted as one block (their evidence is correlated); 0: none.
   */
  double runner_up_error = 0.0;
  double verification_radius = 0.0; ///< meters: half the coarse voxel
  int verification_samples = 0;     ///< source samples verified
  /** \brief Enough samples, verification within PhaserParameters' limits and the
   *  final rank 2.33 runner_up_error above the runner-up's. */
  bool verified = false;
  /** \brief Empty, or why a prior (PhaserParameters::region, max_tilt_deg) refused the
   *  pose the search found and what was returned instead (not converged). */
  std::string refusal;
  std::vector<Hypothesis> hypotheses; ///< every hypothesis, pass-1 peaks first
  int passes = 0;                     ///< passes run
  /// rotations (w, x, y, z) about the estimate and weights, for rotationUncertainty()
  std::vector<Eigen::Vector4d> rotation_samples;
  std::vector<double> rotation_weights;
  StageTimes times;
};

/** \brief What one align() found. On failure (error not empty) transformation is the
 *  guess and the rest keeps its defaults. */
struct PhaserResult {
  std::string error; ///< empty on success, else why nothing was estimated
  /** \brief p_target = T p_source, the guess composed: T = [R, c_t + t - R c_s] *
   *  guess for the estimate (R, t) about the projection centers c_s, c_t. */
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();
  /** \brief The final pose verified and, about centroids, its translation peak is
   *  distinct (min_peak_score, min_normalized_overlap). */
  bool converged = false;
  /// the center used: the requested one, or what Automatic chose
  ProjectionCenter projection_center = ProjectionCenter::SensorOrigin;
  int chosen_hypothesis = 0; ///< index of the hypothesis the estimate was refined from
  /// R c_s, meters: how far a rotation error moves the translation
  Eigen::Vector3d lever_arm = Eigen::Vector3d::Zero();
  /// m^2, target frame: error of the last 3-D correlation's peak under its sidelobes
  Eigen::Matrix3d translation_covariance = Eigen::Matrix3d::Zero();
  /** \brief Covariance of the final pose from its point-to-plane fit, as
   *  poseCovariance(); zero when too few samples match or a direction is unmeasured. */
  Eigen::Matrix<double, 6, 6> fit_covariance = Eigen::Matrix<double, 6, 6>::Zero();
  /** \brief Covariance of the pose error, poseCovariance(result,
   *  rotationUncertainty(result), bandwidth): fit_covariance, else the spectral model;
   *  symmetric positive definite when converged, zero otherwise. */
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  PhaserDiagnostics diagnostics; ///< scores, verification, hypotheses, timings
};

// The one list of a PhaserResult's fields and their names, written by
// `pcl_phaser_align --json`, the records of `pcl_phaser_batch`, the benchmark CSV and
// the Python Result (to_dict() and its pickled state); a new field is declared above
// and listed below, and doc/cli.md names it (a test checks). A visitor is called as
// visitor(name, field) with each field, a reference (const when the result is): double,
// int, bool, std::string, ProjectionCenter, an Eigen matrix or vector, a std::vector,
// or a FieldGroup / FieldList of nested fields. Writers read the fields; a reader (the
// Python state) visits a mutable result and assigns them.

/** \brief Fields nested under one name ("stages_ms"): visit(visitor) visits them. */
template <class Visit>
struct FieldGroup {
  Visit visit;
};

/** \brief A list under one name ("hypotheses"): visit(items[i], visitor) visits the
 *  fields of one item. \tparam Items a reference to a [const] std::vector */
template <class Items, class Visit>
struct FieldList {
  Items items;
  Visit visit;
};

/** \brief A [const] Verification's fields, score and rank as "verification_*". */
template <class T, class Visitor>
void visitVerificationFields(T& v, Visitor&& visitor)
{
  visitor("inlier_fraction", v.inlier_fraction);
  visitor("verification_score", v.score);
  visitor("free_space_violation", v.free_space_violation);
  visitor("reverse_free_space_violation", v.reverse_free_space_violation);
  visitor("constraint", v.constraint);
  visitor("verification_rank", v.rank);
}

/** \brief A [const] StageTimes' milliseconds, by its members' names. */
template <class T, class Visitor>
void visitStageTimes(T& t, Visitor&& visitor)
{
  visitor("target", t.target);
  visitor("sampling", t.sampling);
  visitor("sht", t.sht);
  visitor("so3", t.so3);
  visitor("refinement", t.refinement);
  visitor("translation", t.translation);
  visitor("orientation", t.orientation);
  visitor("verification", t.verification);
}

/** \brief The figures of a [const] PhaserDiagnostics that every writer writes, the
 *  verification's flat; runner_up_rank -infinity: none. */
template <class D, class Visitor>
void visitDiagnosticsFields(D& d, Visitor&& visitor)
{
  visitor("rotation_score", d.rotation_score);
  visitor("translation_score", d.translation_score);
  visitor("normalized_overlap", d.normalized_overlap);
  visitVerificationFields(d.verification, visitor);
  visitor("runner_up_rank", d.runner_up_rank);
  visitor("runner_up_error", d.runner_up_error);
  visitor("verification_radius", d.verification_radius);
  visitor("verification_samples", d.verification_samples);
  visitor("verified", d.verified);
  visitor("refusal", d.refusal);
  visitor("passes", d.passes);
  const auto times = [&t = d.times](auto&& v) { visitStageTimes(t, v); };
  visitor("stages_ms", FieldGroup<decltype(times)>{times});
}

/** \brief The figures of a [const] PhaserResult that every writer writes (the tools
 *  after their "transformation" and "converged"): its covariance and diagnostics. */
template <class R, class Visitor>
void visitResultFields(R& r, Visitor&& visitor)
{
  visitor("covariance", r.covariance);
  visitDiagnosticsFields(r.diagnostics, visitor);
}

/** \brief A [const] Hypothesis's fields by its members' names, the verification's flat.
 */
template <class H, class Visitor>
void visitHypothesisFields(H& h, Visitor&& visitor)
{
  visitor("transformation", h.transformation);
  visitor("rotation", h.rotation);
  visitor("translation", h.translation);
  visitor("rotation_score", h.rotation_score);
  visitor("overlap", h.overlap);
  visitor("from_orientation", h.from_orientation);
  visitVerificationFields(h.verification, visitor);
}

/** \brief Every field of a [const] PhaserResult, what restores it exactly: those of
 *  visitResultFields() and the rest; a hypothesis by visitHypothesisFields(). */
template <class R, class Visitor>
void visitResultState(R& r, Visitor&& visitor)
{
  visitor("error", r.error);
  visitor("transformation", r.transformation);
  visitor("converged", r.converged);
  visitor("projection_center", r.projection_center);
  visitor("chosen_hypothesis", r.chosen_hypothesis);
  visitor("lever_arm", r.lever_arm);
  visitor("translation_covariance", r.translation_covariance);
  visitor("fit_covariance", r.fit_covariance);
  visitResultFields(r, visitor);
  const auto each = [](auto& h, auto&& v) { visitHypothesisFields(h, v); };
  auto& hypotheses = r.diagnostics.hypotheses;
  visitor("hypotheses",
          FieldList<decltype(hypotheses), decltype(each)>{hypotheses, each});
  visitor("rotation_samples", r.diagnostics.rotation_samples);
  visitor("rotation_weights", r.diagnostics.rotation_weights);
}

} // namespace pcl::phaser
