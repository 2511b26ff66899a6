/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * warmUp(): the first align of a process, done ahead on a synthetic scan pair.
 */
#include <pcl_phaser/core/warm_up.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace pcl::phaser {
namespace {

constexpr int kRings = 64;
constexpr double kLowestElevation = -25.0 * M_PI / 180.0;
constexpr double kHighestElevation = 3.0 * M_PI / 180.0;

struct Box {
  Eigen::Vector3d lo, hi;
};
/** The walls, floor and ceiling of a 55 x 35 x 8 m hall around the sensors. */
const Box kHall{{-25.0, -15.0, -1.8}, {30.0, 20.0, 6.2}};
/** Pillars and crates in the hall, placed without symmetry. */
const Box kObstacles[] = {
    {{4.0, 3.0, -1.8}, {5.0, 4.0, 6.2}},     {{-9.0, 6.0, -1.8}, {-8.0, 7.5, 6.2}},
    {{12.0, -8.0, -1.8}, {13.5, -7.0, 6.2}}, {{-6.0, -5.0, -1.8}, {-3.5, -3.0, -0.3}},
    {{18.0, 9.0, -1.8}, {21.0, 10.0, 1.0}},  {{7.0, -3.0, -1.8}, {8.0, -2.2, 0.4}}};

/** Where the ray o + t d (t > 0) enters \a box, or infinity when it misses. */
double entry(const Box& box, const Eigen::Vector3d& o, const Eigen::Vector3d& d)
{
  double near = -std::numeric_limits<double>::infinity();
  double far = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (o[a] < box.lo[a] || o[a] > box.hi[a])
        return std::numeric_limits<double>::infinity();
      continue;
    }
    const double t1 = (box.lo[a] - o[a]) / d[a], t2 = (box.hi[a] - o[a]) / d[a];
    near = std::max(near, std::min(t1, t2));
    far = std::min(far, std::max(t1, t2));
  }
  return near <= far && near > 0.0 ? near : std::numeric_limits<double>::infinity();
}

/** Distance from \a o along the unit ray \a d to the first surface of the hall. */
double castRay(const Eigen::Vector3d& o, const Eigen::Vector3d& d)
{
  double t = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
    if (d[a] != 0.0)
      t = std::min(t, ((d[a] > 0.0 ? kHall.hi[a] : kHall.lo[a]) - o[a]) / d[a]);
  for (const Box& box : kObstacles)
    t = std::min(t, entry(box, o, d));
  return t;
}

/** A 64-ring scan of the hall from \a pose in the sensor frame, with channels. */
SourceCloud syntheticScan(const Eigen::Isometry3d& pose, int points,
                          std::size_t channels)
{
  const int columns = std::max(1, points / kRings);
  SourceCloud scan;
  scan.points.resize(3, static_cast<Eigen::Index>(kRings) * columns);
  scan.channels.assign(channels, Eigen::VectorXd(scan.points.cols()));
  for (int ring = 0; ring < kRings; ++ring) {
    const double elevation =
        kLowestElevation + (kHighestElevation - kLowestElevation) * ring / (kRings - 1);
    for (int column = 0; column < columns; ++column) {
      const double azimuth = 2.0 * M_PI * column / columns;
      const Eigen::Vector3d d(std::cos(elevation) * std::cos(azimuth),
                              std::cos(elevation) * std::sin(azimuth),
                              std::sin(elevation));
      const Eigen::Vector3d world = pose.linear() * d;
      const double range = castRay(pose.translation(), world);
      const Eigen::Index i = static_cast<Eigen::Index>(ring) * columns + column;
      scan.points.col(i) = range * d;
      const Eigen::Vector3d hit = pose.translation() + range * world;
      for (std::size_t c = 0; c < channels; ++c)
        scan.channels[c][i] =
            0.5 + 0.5 * std::sin((1.0 + c) * hit.x()) * std::cos(0.7 * hit.y() + c);
    }
  }
  return scan;
}

} // namespace

std::string warmUp(const PhaserParameters& params, const WarmUpOptions& options)
{
  if (options.channels > 8)
    return "warm-up: channels must be in [0, 8]";
  if (options.points < 1000 || options.points > 2000000)
    return "warm-up: points must be in [1000, 2000000]";
#if defined(__GLIBC__)
  if (options.keep_memory) {
    mallopt(M_ARENA_MAX, 1);
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, INT_MAX);
  }
#endif
  // The repeated work cut, the sizes (and tables, plans, buffers) kept: after it a
  // first align took 3-976 page faults instead of 29,300.
  PhaserParameters cheaper = params;
  cheaper.rotation_candidates = 1;
  cheaper.orientation_candidates = std::min(params.orientation_candidates, 1);
  cheaper.refinement_iterations = std::min(params.refinement_iterations, 1);
  Eigen::Isometry3d source_pose = Eigen::Isometry3d::Identity();
  source_pose.translate(Eigen::Vector3d(0.8, -0.4, 0.0));
  source_pose.rotate(Eigen::AngleAxisd(5.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
  SourceCloud target_scan =
      syntheticScan(Eigen::Isometry3d::Identity(), options.points, options.channels);
  const SourceCloud source_scan =
      syntheticScan(source_pose, options.points, options.channels);
  const Target target(std::move(target_scan.points), std::move(target_scan.channels));
  return align(target, source_scan, Eigen::Matrix4d::Identity(), cheaper).error;
}

} // namespace pcl::phaser
