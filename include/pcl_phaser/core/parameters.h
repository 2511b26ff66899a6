/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <cmath>
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

/** \brief Every setting of one registration, with its default. The range, unit and
 *  meaning of each numeric field are in kParameterRanges (and doc/parameters.md);
 *  validateParameters() checks them at each align() and in pcl::PhaserRegistration's
 *  setters. */
struct PhaserParameters {
  /** \brief Spherical bandwidth B: the sphere is sampled on a 2B x 2B grid and the
   *  SO(3) grid spacing is pi / B before refinement. */
  int bandwidth = 64;
  int spatial_grid_size = 128; ///< the grid is sized to the target with a margin
  double voxel_size = 0.0;     ///< 0: from spatial_grid_size and the target's extent
  /** \brief Newton iterations that refine the rotation peak, on the plain correlation
   *  and again on the normalized one (normalized_refinement). */
  int refinement_iterations = 2;
  int fusion_levels = 5; ///< Laplacian pyramid levels (1: plain average)
  /** \brief Distinct peaks of the range correlation taken through the translation
   *  stage in pass 1; more than one matters for symmetric scenes. */
  int rotation_candidates = 3;
  /** \brief Passes, at most. Pass 1 projects each cloud about its own center; each
   *  further pass projects the source, moved by the estimate, about the target's
   *  center and measures the residual shift on a fine grid over the target's inner
   *  region. They stop once a shift update is below a quarter of a fine voxel. */
  int passes = 3;
  /** \brief Worker threads; 0: one per hardware thread (at most 64), PCL's
   *  convention. Results are bit-identical for any count. */
  int num_threads = 0;
  /** \brief Refine the rotation again on the energy-normalized SO(3) correlation,
   *  within 0.75 deg x 64 / B of the maximum of the plain one, when the clouds are
   *  projected about their sensor origins (about centroids the plain refinement is
   *  kept), against the pull of the field-of-view edges toward equal sensor tilt
   *  (measured on simulated LiDAR pairs). Default true. */
  bool normalized_refinement = true;
  /** \brief Rotation hypotheses from the surface-orientation histograms, tried beside
   *  the range peaks about sensor origins. When the best of them would not be
   *  claimed, the next ten peaks of the histograms are tried as well. Two scans of
   *  one place taken apart need them: on real revisits fewer made an align faster
   *  and failed more of them. */
  int orientation_candidates = 10;
  int orientation_bandwidth = 32; ///< of the orientation histograms
  double whitening = 0.5; ///< exponent of the cross-power whitening, translation search
  /** \brief Where both clouds are projected on the sphere. */
  ProjectionCenter projection_center = ProjectionCenter::SensorOrigin;
  /** \brief Channel switches: the pcl::phaser::Channel flags of the point fields
   *  pcl::PhaserRegistration may fuse (those both point types carry); all by default.
   *  The engine fuses whatever ChannelValues it is given. */
  std::uint32_t channels = ~0u;
  /** \brief Verification: least (weighted) share of the source samples with a target
   *  point within the verification radius whose normal agrees. */
  double min_inlier_fraction = 0.2;
  /** \brief Verification about sensor origins: largest share of source samples in
   *  space the target's sensor saw through, and of target samples in space the
   *  source's sensor saw through. */
  double max_free_space_violation = 0.02;
  /** \brief Verification: least PhaserResult::constraint, the smallest eigenvalue of
   *  the matched normals' scatter (at most 1/3). */
  double min_constraint = 0.04;
  /** \brief About centroids, converged also needs a translation peak score (the
   *  peak-to-sidelobe ratio of the final 3-D correlation) of at least this ... */
  double min_peak_score = 20.0;
  /** \brief ... or half of it with a normalized overlap of at least this (both
   *  defaults separate right from wrong poses on measured pairs). */
  double min_normalized_overlap = 0.55;
};

/** \brief One row of kParameterRanges: a numeric field of PhaserParameters. */
struct ParameterRange {
  const char* name;               ///< the field's name
  int PhaserParameters::*integer; ///< the field when it is an int, else null
  double PhaserParameters::*real; ///< the field when it is a double, else null
  double min, max;                ///< inclusive; max inf: no upper bound
  const char *unit, *meaning;     ///< unit ("" when none), one-line meaning
  double value(const PhaserParameters& p) const
  {
    return integer ? p.*integer : p.*real;
  }
};

/** \brief The legal range of every numeric field of PhaserParameters (the defaults are
 *  the fields' initializers). */
inline constexpr ParameterRange kParameterRanges[] = {
    // B = 1 keeps only degree 0, a constant on the sphere: no rotation to find.
    {"bandwidth", &PhaserParameters::bandwidth, nullptr, 2, 256, "",
     "spherical bandwidth B: a 2B x 2B grid on the sphere"},
    {"spatial_grid_size", &PhaserParameters::spatial_grid_size, nullptr, 8, 1024,
     "voxels", "translation grid, longest axis; ignored when voxel_size > 0"},
    {"voxel_size", nullptr, &PhaserParameters::voxel_size, 0, HUGE_VAL, "m",
     "voxel edge of the translation grid; 0: from spatial_grid_size"},
    {"refinement_iterations", &PhaserParameters::refinement_iterations, nullptr, 0, 10,
     "", "Newton iterations refining the rotation peak"},
    {"fusion_levels", &PhaserParameters::fusion_levels, nullptr, 1, 8, "",
     "pyramid levels of the channel fusion (1: plain average)"},
    {"rotation_candidates", &PhaserParameters::rotation_candidates, nullptr, 1, 10, "",
     "range-correlation peaks taken through the translation search"},
    {"passes", &PhaserParameters::passes, nullptr, 1, 5, "", "registration passes"},
    {"num_threads", &PhaserParameters::num_threads, nullptr, 0, 64, "",
     "worker threads (0: one per hardware thread)"},
    {"orientation_candidates", &PhaserParameters::orientation_candidates, nullptr, 0,
     20, "", "rotation hypotheses from the orientation histograms (0: none)"},
    {"orientation_bandwidth", &PhaserParameters::orientation_bandwidth, nullptr, 8, 128,
     "", "bandwidth of the surface-orientation histograms"},
    {"whitening", nullptr, &PhaserParameters::whitening, 0, 1, "",
     "translation search: 0 plain correlation, 1 phase correlation"},
    {"min_inlier_fraction", nullptr, &PhaserParameters::min_inlier_fraction, 0, 1, "",
     "verification: least share of source samples on the target"},
    {"max_free_space_violation", nullptr, &PhaserParameters::max_free_space_violation,
     0, 1, "", "verification: largest share of samples in seen-through space"},
    {"min_constraint", nullptr, &PhaserParameters::min_constraint, 0, 1.0 / 3.0, "",
     "verification: least constraint of the translation in every direction"},
    {"min_peak_score", nullptr, &PhaserParameters::min_peak_score, 0, HUGE_VAL, "",
     "about centroids: least translation peak-to-sidelobe ratio"},
    {"min_normalized_overlap", nullptr, &PhaserParameters::min_normalized_overlap, 0, 1,
     "", "about centroids: least overlap that lets half that score do"}};

/** \brief The row of field \a name in kParameterRanges; null when there is none. */
const ParameterRange* findParameterRange(const std::string& name);

/** \brief The worker threads \a num_threads stands for: itself, or for 0 one per
 *  hardware thread (at most 64). */
int resolveThreadCount(int num_threads);

/** \brief Empty when every field of \a p is in its range (kParameterRanges), else the
 *  first field that is not, its value, its range and what it means. */
std::string validateParameters(const PhaserParameters& p);

} // namespace pcl::phaser
