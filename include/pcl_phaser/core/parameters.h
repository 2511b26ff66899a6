/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>

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

/** \brief The signal channels pcl::PhaserRegistration fuses, as bit flags. */
enum Channel : std::uint32_t {
  CHANNEL_RANGE = 1u << 0,        ///< |p| from xyz (always available)
  CHANNEL_INTENSITY = 1u << 1,    ///< the `intensity` field
  CHANNEL_REFLECTIVITY = 1u << 2, ///< the `reflectivity` field (Ouster)
  CHANNEL_AMBIENT = 1u << 3,      ///< the `ambient` field (Ouster near-IR)
  CHANNEL_COLOR = 1u << 4         ///< luminance of `rgb`/`rgba`
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

/** \brief Every setting of one registration, with its default; each field's type,
 *  range, unit and meaning: kParameterRanges, checked by validateParameters(). */
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

/** \brief What a row of kParameterRanges holds. */
enum class ParameterType {
  Integer, ///< an int in min..max
  Real,    ///< a double in min..max
  Boolean, ///< a bool: true, false (the tools also take on/off, yes/no, 1/0)
  Choice,  ///< an enum: one of the row's names
  Flags    ///< bit flags: any of the row's names, `all`, or a number in min..max
};

/** \brief One named value of a Choice row, or one named bit of a Flags row. */
struct ParameterName {
  const char* name;       ///< as the tools write and read it, e.g. "sensor"
  const char* identifier; ///< the C++ enumerator, e.g. "SensorOrigin"
  std::uint32_t value;    ///< its value, or its bit
};

/** \brief The names of ProjectionCenter's values. */
inline constexpr ParameterName kProjectionCenterNames[] = {
    {"sensor", "SensorOrigin", std::uint32_t(ProjectionCenter::SensorOrigin)},
    {"centroid", "Centroid", std::uint32_t(ProjectionCenter::Centroid)},
    {"auto", "Automatic", std::uint32_t(ProjectionCenter::Automatic)}};

/** \brief The names of the Channel flags. */
inline constexpr ParameterName kChannelNames[] = {
    {"range", "CHANNEL_RANGE", CHANNEL_RANGE},
    {"intensity", "CHANNEL_INTENSITY", CHANNEL_INTENSITY},
    {"reflectivity", "CHANNEL_REFLECTIVITY", CHANNEL_REFLECTIVITY},
    {"ambient", "CHANNEL_AMBIENT", CHANNEL_AMBIENT},
    {"color", "CHANNEL_COLOR", CHANNEL_COLOR}};

/** \brief One row of kParameterRanges: a field of PhaserParameters or of its region,
 *  its type, range, unit and meaning. Every value passes as a double (exact for each
 *  type: int, bool as 0 / 1, an enum's or the flags' integer). */
struct ParameterRange {
  const char* name;                       ///< the field's name
  ParameterType type;                     ///< what it holds
  double min, max;                        ///< inclusive; max inf: no upper bound
  const char* unit;                       ///< unit ("" when none)
  const char* meaning;                    ///< one-line meaning
  double (*get)(const PhaserParameters&); ///< reads the field
  void (*put)(PhaserParameters&, double); ///< writes the field
  const ParameterName* names = nullptr;   ///< a Choice's values, a Flags' bits
  std::size_t name_count = 0;             ///< how many names
  bool in_region = false;                 ///< a field of PhaserParameters::region
  bool changes_results = true; ///< false: results are bit-identical at any value
  /** \brief The field's value; a region's field is 0 without a region. */
  double value(const PhaserParameters& p) const { return get(p); }
  /** \brief Sets the field to \a v (an int field to its integer part, a value beyond
   *  the field's type to the nearest it holds). A region's field set to nonzero makes
   *  the region; its radius set to 0 removes it. */
  void set(PhaserParameters& p, double v) const { put(p, v); }
  /** \brief This row, marked as not changing results (num_threads). */
  constexpr ParameterRange sameResults() const
  {
    ParameterRange r = *this;
    r.changes_results = false;
    return r;
  }
};

namespace detail {

template <class M>
struct MemberOf;
template <class C, class T>
struct MemberOf<T C::*> {
  using Class = C;
  using Type = T;
};

/** \brief \a v as a T: an integer saturated to T's limits (NaN: the lowest), a bool
 *  v != 0. */
template <class T>
T fieldValue(double v)
{
  if constexpr (std::is_same_v<T, bool> || std::is_floating_point_v<T>)
    return static_cast<T>(v);
  else if constexpr (std::is_enum_v<T>)
    return static_cast<T>(fieldValue<std::underlying_type_t<T>>(v));
  else {
    const double lo = static_cast<double>(std::numeric_limits<T>::lowest());
    const double hi = static_cast<double>(std::numeric_limits<T>::max());
    return v >= lo ? (v <= hi ? static_cast<T>(v) : std::numeric_limits<T>::max())
                   : std::numeric_limits<T>::lowest(); // NaN too
  }
}

template <auto F>
double readField(const PhaserParameters& p)
{
  if constexpr (std::is_same_v<typename MemberOf<decltype(F)>::Class, Region>)
    return p.region ? (*p.region).*F : 0.0;
  else
    return static_cast<double>(p.*F);
}

template <auto F>
void writeField(PhaserParameters& p, double v)
{
  using Member = MemberOf<decltype(F)>;
  if constexpr (std::is_same_v<typename Member::Class, Region>) {
    if (F == &Region::radius && v == 0.0)
      p.region.reset();
    else if (p.region || v != 0.0) {
      if (!p.region) // (GCC 12 copies the region of `(c ? a : b).*F = v`)
        p.region.emplace();
      (*p.region).*F = v;
    }
  } else
    p.*F = fieldValue<typename Member::Type>(v);
}

template <class T>
constexpr ParameterType typeOf()
{
  if constexpr (std::is_same_v<T, bool>)
    return ParameterType::Boolean;
  else if constexpr (std::is_enum_v<T>)
    return ParameterType::Choice;
  else if constexpr (std::is_unsigned_v<T>)
    return ParameterType::Flags;
  else
    return std::is_integral_v<T> ? ParameterType::Integer : ParameterType::Real;
}

} // namespace detail

/** \brief The row of field \a F (a member of PhaserParameters or of Region) called
 *  \a name: int, double or bool (range 0..1). */
template <auto F>
constexpr ParameterRange parameterRow(const char* name, double min, double max,
                                      const char* unit, const char* meaning)
{
  using Member = detail::MemberOf<decltype(F)>;
  return {name,
          detail::typeOf<typename Member::Type>(),
          min,
          max,
          unit,
          meaning,
          &detail::readField<F>,
          &detail::writeField<F>,
          nullptr,
          0,
          std::is_same_v<typename Member::Class, Region>};
}

/** \brief The row of field \a F called \a name: an enum (one of \a names) or flags
 *  (any of \a names, range 0..max of the field's type). */
template <auto F, std::size_t N>
constexpr ParameterRange parameterRow(const char* name, const ParameterName (&names)[N],
                                      const char* meaning)
{
  using Type = typename detail::MemberOf<decltype(F)>::Type;
  ParameterRange r = parameterRow<F>(name, 0, 0, "", meaning);
  r.names = names;
  r.name_count = N;
  if constexpr (std::is_enum_v<Type>) {
    r.min = r.max = names[0].value;
    for (const ParameterName& n : names)
      r.min = n.value < r.min ? n.value : r.min,
      r.max = n.value > r.max ? n.value : r.max;
  } else
    r.max = static_cast<double>(std::numeric_limits<Type>::max());
  return r;
}

/** \brief Every setting of PhaserParameters, typed, with its range, unit and meaning,
 *  in the order of the fields: what validateParameters() checks, the tools' engine
 *  options, the Python Parameters, the batch's run fingerprint and doc/parameters.md
 *  are made of. */
inline constexpr ParameterRange kParameterRanges[] = {
    // B = 1 keeps only degree 0, a constant on the sphere: no rotation to find.
    parameterRow<&PhaserParameters::bandwidth>(
        "bandwidth", 2, 256, "", "spherical bandwidth B: a 2B x 2B grid on the sphere"),
    parameterRow<&PhaserParameters::spatial_grid_size>(
        "spatial_grid_size", 8, 1024, "voxels",
        "translation grid, longest axis; ignored when voxel_size > 0"),
    parameterRow<&PhaserParameters::voxel_size>(
        "voxel_size", 0, HUGE_VAL, "m",
        "voxel edge of the translation grid; 0: from spatial_grid_size"),
    parameterRow<&PhaserParameters::refinement_iterations>(
        "refinement_iterations", 0, 10, "",
        "Newton iterations refining the rotation peak"),
    parameterRow<&PhaserParameters::fusion_levels>(
        "fusion_levels", 1, 8, "",
        "pyramid levels of the channel fusion (1: plain average)"),
    parameterRow<&PhaserParameters::rotation_candidates>(
        "rotation_candidates", 1, 10, "",
        "range-correlation peaks taken through the translation search"),
    parameterRow<&PhaserParameters::passes>("passes", 1, 5, "", "registration passes"),
    parameterRow<&PhaserParameters::num_threads>(
        "num_threads", 0, 64, "", "worker threads (0: one per hardware thread)")
        .sameResults(),
    parameterRow<&PhaserParameters::normalized_refinement>(
        "normalized_refinement", 0, 1, "",
        "about sensor origins, refine the rotation again on the normalized "
        "correlation"),
    parameterRow<&PhaserParameters::orientation_candidates>(
        "orientation_candidates", 0, 20, "",
        "rotation hypotheses from the orientation histograms (0: none)"),
    parameterRow<&PhaserParameters::orientation_bandwidth>(
        "orientation_bandwidth", 8, 128, "",
        "bandwidth of the surface-orientation histograms"),
    parameterRow<&PhaserParameters::whitening>(
        "whitening", 0, 1, "",
        "translation search: 0 plain correlation, 1 phase correlation"),
    parameterRow<&PhaserParameters::projection_center>(
        "projection_center", kProjectionCenterNames,
        "projection center: sensor (each cloud's origin: scans), centroid, or auto "
        "(sensor when they look like scans)"),
    parameterRow<&PhaserParameters::channels>(
        "channels", kChannelNames,
        "channels pcl::PhaserRegistration fuses when the clouds have them"),
    parameterRow<&PhaserParameters::min_inlier_fraction>(
        "min_inlier_fraction", 0, 1, "",
        "verification: least share of source samples on the target"),
    parameterRow<&PhaserParameters::max_free_space_violation>(
        "max_free_space_violation", 0, 1, "",
        "verification: largest share of samples in seen-through space"),
    parameterRow<&PhaserParameters::min_constraint>(
        "min_constraint", 0, 1.0 / 3.0, "",
        "verification: least constraint of the translation in every direction"),
    parameterRow<&PhaserParameters::min_peak_score>(
        "min_peak_score", 0, HUGE_VAL, "",
        "about centroids: least translation peak-to-sidelobe ratio"),
    parameterRow<&PhaserParameters::min_normalized_overlap>(
        "min_normalized_overlap", 0, 1, "",
        "about centroids: least overlap that lets half that score do"),
    parameterRow<&Region::radius>("region_radius", 0, 1e5, "m",
                                  "position prior: the source's sensor is this close "
                                  "to the region center (0: off)"),
    parameterRow<&Region::x>("region_x", -1e6, 1e6, "m",
                             "position prior: region center, target frame"),
    parameterRow<&Region::y>("region_y", -1e6, 1e6, "m",
                             "position prior: region center, target frame"),
    parameterRow<&Region::z>("region_z", -1e6, 1e6, "m",
                             "position prior: region center, target frame"),
    parameterRow<&Region::sensor_range>(
        "sensor_range", 0, 1e4, "m",
        "position prior: target points within region_radius + this are used (0: auto)"),
    parameterRow<&PhaserParameters::max_tilt_deg>(
        "max_tilt_deg", 0, 180, "deg",
        "gravity prior: largest tilt of the rotation searched (0: off)")};

/** \brief The row of field \a name in kParameterRanges; null when there is none. */
const ParameterRange* findParameterRange(const std::string& name);

/** \brief \a v, a value of row \a r, as the tools write and read it: a number with
 *  \a digits significant digits, true or false, a Choice's name, a Flags' names joined
 *  by ',' ("all" when every bit is set, the number when a bit has no name). */
std::string parameterText(const ParameterRange& r, double v, int digits = 6);

/** \brief \a text as a value of row \a r into \a v: a number (an integer for an
 *  Integer row), true / false (on / off, yes / no, 1 / 0), a Choice's name (with
 *  \a enumerators its enumerator in snake case too: "sensor_origin"), a Flags' names
 *  joined by ',', "all" or a number. \return false, \a v unchanged, when it is none of
 *  them or is outside the row's range */
bool parseParameter(const ParameterRange& r, const std::string& text, double& v,
                    bool enumerators = false);

/** \brief The values row \a r takes, short: "2..256", "true, false", a Choice's names
 *  joined by ", ", "all, or any of " a Flags' names. */
std::string parameterValues(const ParameterRange& r);

/** \brief What row \a r takes, for a message after "expected": "an integer in
 *  2..256", "degrees in 0..180", "true or false", "one of sensor, centroid, auto", ...
 */
std::string parameterDomain(const ParameterRange& r);

/** \brief \a num_threads, or for 0 one per hardware thread (at most 64). */
int resolveThreadCount(int num_threads);

/** \brief Empty when every field of \a p is in its range (an enum: one of its names),
 *  else the first that is not, its value, range and meaning. */
std::string validateParameters(const PhaserParameters& p);

} // namespace pcl::phaser
