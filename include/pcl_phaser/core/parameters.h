/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

namespace pcl::phaser {

/** \brief Where the clouds are projected on the sphere. */
enum class ProjectionCenter {
  SensorOrigin, ///< each cloud's frame origin (LiDAR scans in their sensor frame)
  Centroid,     ///< each cloud's centroid (object scans, clouds far from their origin)
  /** The default: SensorOrigin when the source looks like a scan seen from its frame
   *  origin (its nearest point within half its bounding-box diagonal of it) and so
   *  does the target or the target's origin is off its data (a map in a site frame),
   *  else Centroid (see PhaserResult::projection_center). */
  Automatic
};

/** \brief A position prior: the source's sensor, its frame origin after the guess, lies
 *  within radius of (x, y, z) in the target's frame. Only target points a sensor there
 *  could see are used, the translation search covers the region, and a pose outside it
 *  is never returned. The source is projected about its sensor, the target about the
 *  region's center, whatever projection_center says. */
struct Region {
  double x = 0.0, y = 0.0, z = 0.0; ///< the center, meters, target frame
  double radius = 0.0;              ///< meters, > 0
  /** \brief Target points farther than radius + this from the center are left out;
   *  0: the source's 99th-percentile range, rounded up to 10 m. */
  double sensor_range = 0.0;
};

/** \brief Every setting of one registration, with its default; the numeric fields'
 *  ranges, units, meanings: kParameterRanges, checked by validateParameters(). */
struct PhaserParameters {
  int bandwidth = 64;            ///< SO(3) grid spacing pi / B before refinement
  int spatial_grid_size = 128;   ///< the grid is sized to the target with a margin
  double voxel_size = 0.0;       ///< 0: from spatial_grid_size and the target's extent
  int refinement_iterations = 2; ///< and as many again for normalized_refinement
  int fusion_levels = 5;         ///< Laplacian pyramid
  int rotation_candidates = 3;   ///< in pass 1; more than one for symmetric scenes
  /** \brief Passes, at most: each after the first projects the moved source about the
   *  target's center and refines the shift, until it changes by < 1/4 fine voxel. */
  int passes = 3;
  int num_threads = 0; ///< results are bit-identical for any count
  /** \brief About sensor origins, refine the rotation again on the energy-normalized
   *  SO(3) correlation, within 0.75 deg x 64 / B of the plain maximum, against the pull
   *  of the field-of-view edges toward equal sensor tilt. */
  bool normalized_refinement = true;
  /** \brief Tried beside the range peaks about sensor origins; when the best would not
   *  be claimed, the next ten histogram peaks as well. */
  int orientation_candidates = 10;
  int orientation_bandwidth = 32;
  double whitening = 0.5; ///< exponent of the cross-power whitening
  ProjectionCenter projection_center = ProjectionCenter::Automatic;
  /** \brief The pcl::phaser::Channel flags pcl::PhaserRegistration may fuse; the
   *  engine fuses whatever ChannelValues it is given. */
  std::uint32_t channels = ~0u;
  double min_inlier_fraction = 0.2;       ///< weighted; the target's normal must agree
  double max_free_space_violation = 0.02; ///< about sensor origins, both ways
  double min_constraint = 0.04;           ///< of diagnostics.verification.constraint
  double min_peak_score = 20.0;           ///< of diagnostics.translation_score ...
  double min_normalized_overlap = 0.55;   ///< ... or half that score and this overlap
  /** \brief Position prior (a GNSS fix, the last known pose); none by default. */
  std::optional<Region> region;
  /** \brief Gravity prior, degrees (0: off). Both clouds are z-up after the guess (or
   *  the guess makes them so) up to this tilt: only rotations tilting the source by
   *  less are searched, and a result tilted more is replaced by the best hypothesis
   *  within it and not converged. Wrong for a rig held at an angle. */
  double max_tilt_deg = 0.0;
};

/** \brief One row of kParameterRanges: a numeric field of PhaserParameters or of its
 *  region. */
struct ParameterRange {
  const char* name;                    ///< the field's name
  int PhaserParameters::*integer;      ///< the field when it is an int, else null
  double PhaserParameters::*real;      ///< the field when it is a double, else null
  double min, max;                     ///< inclusive; max inf: no upper bound
  const char *unit, *meaning;          ///< unit ("" when none), one-line meaning
  double Region::*in_region = nullptr; ///< the field when it is the region's, else null
  /** \brief The field's value; a region's field is 0 without a region. */
  double value(const PhaserParameters& p) const
  {
    if (integer || real)
      return integer ? p.*integer : p.*real;
    return p.region ? (*p.region).*in_region : 0.0;
  }
  /** \brief Sets the field to \a v (an int field to its integer part). A region's
   *  field set to nonzero makes the region; its radius set to 0 removes it. */
  void set(PhaserParameters& p, double v) const
  {
    if (integer)
      p.*integer = static_cast<int>(v);
    else if (real)
      p.*real = v;
    else if (in_region == &Region::radius && v == 0.0)
      p.region.reset();
    else if (p.region || v != 0.0) {
      Region& region = p.region ? *p.region : p.region.emplace();
      region.*in_region = v;
    }
  }
};

/** \brief The legal range of every numeric field of PhaserParameters. */
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
     "", "about centroids: least overlap that lets half that score do"},
    {"region_radius", nullptr, nullptr, 0, 1e5, "m",
     "position prior: the source's sensor is this close to the region center (0: off)",
     &Region::radius},
    {"region_x", nullptr, nullptr, -1e6, 1e6, "m",
     "position prior: region center, target frame", &Region::x},
    {"region_y", nullptr, nullptr, -1e6, 1e6, "m",
     "position prior: region center, target frame", &Region::y},
    {"region_z", nullptr, nullptr, -1e6, 1e6, "m",
     "position prior: region center, target frame", &Region::z},
    {"sensor_range", nullptr, nullptr, 0, 1e4, "m",
     "position prior: target points within region_radius + this are used (0: auto)",
     &Region::sensor_range},
    {"max_tilt_deg", nullptr, &PhaserParameters::max_tilt_deg, 0, 180, "deg",
     "gravity prior: largest tilt of the rotation searched (0: off)"}};

/** \brief The row of field \a name in kParameterRanges; null when there is none. */
const ParameterRange* findParameterRange(const std::string& name);

/** \brief \a num_threads, or for 0 one per hardware thread (at most 64). */
int resolveThreadCount(int num_threads);

/** \brief Empty when every field of \a p is in its range, else the first that is not,
 *  its value, range and meaning. */
std::string validateParameters(const PhaserParameters& p);

} // namespace pcl::phaser
