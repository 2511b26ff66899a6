/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <cstdint>
#include <string>

namespace pcl::phaser {

/** \brief Where the clouds are projected on the sphere. */
enum class ProjectionCenter {
  SensorOrigin, ///< the origin of each cloud's frame (LiDAR scans in their sensor
                ///< frame)
  Centroid,     ///< each cloud's centroid (object scans, clouds far from their origin)
  /** SensorOrigin when both clouds look like spinning-LiDAR scans in their sensor frame
   *  (they surround their origin in a band with empty poles), else Centroid;
   *  PhaserResult::projection_center tells which. */
  Automatic
};

/** \brief Every setting of one registration, with its default. Ranges are checked once
 *  per align() (validateParameters); an illegal value makes align() fail cleanly. */
struct PhaserParameters {
  /** \brief Spherical bandwidth B, 1..256: the sphere is sampled on a 2B x 2B grid and
   *  the SO(3) grid spacing is pi / B before refinement. */
  int bandwidth = 64;
  /** \brief Voxels along the longest axis of the translation grid, 8..1024; the grid is
   *  sized to the target with a margin. Ignored when voxel_size > 0. */
  int spatial_grid_size = 128;
  /** \brief Voxel edge in meters, >= 0; 0 derives it from spatial_grid_size and the
   *  extent of the target. */
  double voxel_size = 0.0;
  /** \brief Newton iterations that refine the rotation peak, 0..10, on the plain
   *  correlation and again on the normalized one (normalized_refinement). */
  int refinement_iterations = 2;
  /** \brief Laplacian pyramid levels of the channel fusion, 1..8 (1: plain average). */
  int fusion_levels = 5;
  /** \brief Distinct peaks of the range correlation taken through the translation
   *  stage in pass 1, 1..10; more than one matters for symmetric scenes. */
  int rotation_candidates = 3;
  /** \brief Passes, 1..5, at most. Pass 1 projects each cloud about its own center;
   *  each further pass projects the source, moved by the estimate, about the target's
   *  center and measures the residual shift on a fine grid over the target's inner
   *  region. They stop once a shift update is below a quarter of a fine voxel. */
  int passes = 3;
  /** \brief Worker threads, 0..64; 0: one per hardware thread (at most 64), PCL's
   *  convention. Results are bit-identical for any count. */
  int num_threads = 0;
  /** \brief Refine the rotation again on the energy-normalized SO(3) correlation,
   *  within 0.75 deg x 64 / B of the maximum of the plain one, when the clouds are
   *  projected about their sensor origins (about centroids the plain refinement is
   *  kept), against the pull of the field-of-view edges toward equal sensor tilt
   *  (measured in doc/benchmarks.md section 6). Default true. */
  bool normalized_refinement = true;
  /** \brief Rotation hypotheses from the surface-orientation histograms, tried beside
   *  the range peaks about sensor origins, 0..20 (0: none). When the best of them
   *  would not be claimed, the next ten peaks of the histograms are tried as well.
   *  Two scans of one place taken apart need them: fewer make an align faster and
   *  fail more revisits (doc/benchmarks.md 11.21). */
  int orientation_candidates = 10;
  /** \brief Bandwidth of the orientation histograms, 8..128. */
  int orientation_bandwidth = 32;
  /** \brief Exponent of the cross-power whitening of the global translation search,
   *  in [0, 1] (0: plain correlation, 1: phase correlation). */
  double whitening = 0.5;
  /** \brief Where both clouds are projected on the sphere. */
  ProjectionCenter projection_center = ProjectionCenter::SensorOrigin;
  /** \brief Channel switches: the pcl::phaser::Channel flags of the point fields
   *  pcl::PhaserRegistration may fuse (those both point types carry); all by default.
   *  The engine fuses whatever ChannelValues it is given. */
  std::uint32_t channels = ~0u;
  /** \brief Verification: least (weighted) share of the source samples with a target
   *  point within the verification radius whose normal agrees, in [0, 1]. */
  double min_inlier_fraction = 0.2;
  /** \brief Verification about sensor origins: largest share of source samples in
   *  space the target's sensor saw through, and of target samples in space the
   *  source's sensor saw through, in [0, 1]. */
  double max_free_space_violation = 0.02;
  /** \brief Verification: least PhaserResult::constraint (how well the matched samples
   *  pin the translation down in every direction), in [0, 1/3]. */
  double min_constraint = 0.04;
  /** \brief About centroids, converged also needs a translation peak score (the
   *  peak-to-sidelobe ratio of the final 3-D correlation) of at least this, >= 0 ...
   *  (the figures behind these defaults: doc/benchmarks.md section 10) */
  double min_peak_score = 20.0;
  /** \brief ... or half of it with a normalized overlap of at least this, in [0, 1]
   *  (doc/benchmarks.md section 5). */
  double min_normalized_overlap = 0.55;
};

/** \brief The worker threads \a num_threads stands for: itself, or for 0 one per
 *  hardware thread (at most 64). */
int resolveThreadCount(int num_threads);

/** \brief Empty when every field of \a p is in its range, else the reason. */
std::string validateParameters(const PhaserParameters& p);

} // namespace pcl::phaser
