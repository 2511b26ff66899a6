/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_bench revisits: the global aligners on the real revisit pairs of
 * lidar/balm_handheld (two scans of one place taken meters apart, reference poses from
 * LiDAR-inertial odometry), binned by the distance between the scans.
 *
 * The pairs come from pairs.txt or, with --derived-pairs, are derived from the poses of
 * poses_T_world_lidar.txt; the reading and the derivation are header-only here so that
 * the tests can check them without the binary.
 */
#pragma once

#include "text_lines.h"

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace pcl::phaser {
namespace bench {

/** \brief One revisit pair: scan file names, the distance between the scans (m), their
 * relative rotation (deg), the overlap proxy of pairs.txt (NaN for derived pairs). */
struct RevisitPair {
  std::string source, target;
  double dist = 0.0, rel_rot = 0.0, overlap = 0.0;
  Eigen::Matrix4d truth = Eigen::Matrix4d::Identity(); ///< T_target_source
};

/** \brief One line of poses_T_world_lidar.txt: scan full<index>.pcd, T_world_lidar. */
struct ScanPose {
  int index = 0;
  Eigen::Matrix4d world_lidar = Eigen::Matrix4d::Identity();
};

/** \brief Parses "source target dist rot overlap" and 16 numbers; false if malformed.
 */
inline bool parsePairLine(const std::string& line, RevisitPair& pair)
{
  std::istringstream in(line);
  if (!(in >> pair.source >> pair.target >> pair.dist >> pair.rel_rot >> pair.overlap))
    return false;
  for (int i = 0; i < 16; ++i)
    if (!(in >> pair.truth(i / 4, i % 4)))
      return false;
  std::string rest;
  return !(in >> rest) && pair.truth.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1));
}

/** \brief Appends the pairs of a pairs file; false with \a error (forEachLine()) when
 *  it cannot be read or a line is malformed. */
inline bool readPairs(const std::string& path, std::vector<RevisitPair>& pairs,
                      std::string& error)
{
  error = forEachLine(path, [&](const std::string& line, int) -> std::string {
    RevisitPair pair;
    if (!parsePairLine(line, pair))
      return "expected 'source target dist_m rel_rot_deg overlap' and 16 numbers of a "
             "4x4 pose";
    pairs.push_back(pair);
    return "";
  });
  return error.empty();
}

/** \brief Appends the poses of a poses file ("scan_index timestamp" and the 12 numbers
 * of a row-major 3x4 T_world_lidar); false with \a error on a malformed line. */
inline bool readScanPoses(const std::string& path, std::vector<ScanPose>& poses,
                          std::string& error)
{
  error = forEachLine(path, [&](const std::string& line, int) -> std::string {
    std::istringstream in(line);
    ScanPose pose;
    double timestamp = 0.0;
    bool ok = (in >> pose.index >> timestamp) && pose.index >= 0;
    for (int i = 0; ok && i < 12; ++i)
      ok = static_cast<bool>(in >> pose.world_lidar(i / 4, i % 4));
    std::string rest;
    if (!ok || in >> rest)
      return "expected 'scan_index timestamp' and 12 numbers of a 3x4 pose";
    poses.push_back(pose);
    return "";
  });
  return error.empty();
}

constexpr int kDerivedMinGap = 18;      ///< |source - target| scan index, a revisit
constexpr std::size_t kDerivedBins = 4; ///< [3, 5), [5, 10), [10, 15), [15, 21] m
constexpr std::array<double, kDerivedBins + 1> kDerivedEdges = {3, 5, 10, 15, 21};

/** \brief The derivation bin of a distance (the last bin is closed), or -1. */
inline int derivedBin(double dist)
{
  for (std::size_t b = 0; b < kDerivedBins; ++b)
    if (dist >= kDerivedEdges[b] &&
        (dist < kDerivedEdges[b + 1] ||
         (b + 1 == kDerivedBins && dist <= kDerivedEdges[b + 1])))
      return static_cast<int>(b);
  return -1;
}

/** \brief A uniform integer in [0, n), n >= 1, without modulo: the 32 random bits of
 * an mt19937 draw masked to the bits of n - 1, rejected until below n. Unlike
 * std::uniform_int_distribution the same on every standard library. */
inline std::uint32_t uniformBelow(std::mt19937& rng, std::uint32_t n)
{
  std::uint32_t mask = n - 1;
  for (int shift = 1; shift < 32; shift <<= 1)
    mask |= mask >> shift;
  for (;;) {
    const auto draw = static_cast<std::uint32_t>(rng()) & mask;
    if (draw < n)
      return draw;
  }
}

/** \brief Fisher-Yates shuffle with uniformBelow() (std::shuffle's sequence is not
 * specified by the standard). */
template <typename T>
void fisherYates(std::vector<T>& items, std::mt19937& rng)
{
  for (std::size_t i = items.size(); i > 1; --i)
    std::swap(items[i - 1], items[uniformBelow(rng, static_cast<std::uint32_t>(i))]);
}

/** \brief How many ordered candidates each derivation bin had, and how many were taken.
 */
struct DerivedCounts {
  std::array<int, kDerivedBins> candidates{}, chosen{};
};

/** \brief Held-out revisit pairs from the poses: ordered pairs (source i, target j)
 * with |i - j| >= kDerivedMinGap and a distance in a derivation bin, neither (i, j) nor
 * (j, i) in \a listed (compared by file name), shuffled by fisherYates() with
 * std::mt19937(seed), then the first \a per_bin of each bin, skipping the reverse of a
 * pair already taken. T_target_source = T_world_target^-1 * T_world_source. */
inline std::vector<RevisitPair> derivePairs(const std::vector<ScanPose>& poses,
                                            const std::vector<RevisitPair>& listed,
                                            int per_bin, unsigned seed,
                                            DerivedCounts* counts = nullptr)
{
  auto file = [](const std::string& name) {
    return std::filesystem::path(name).filename().string();
  };
  std::set<std::pair<std::string, std::string>> taken;
  for (const RevisitPair& p : listed) {
    taken.insert({file(p.source), file(p.target)});
    taken.insert({file(p.target), file(p.source)});
  }
  DerivedCounts count;
  std::vector<RevisitPair> candidates, chosen;
  for (const ScanPose& source : poses)
    for (const ScanPose& target : poses) {
      RevisitPair p;
      p.source = "full" + std::to_string(source.index) + ".pcd";
      p.target = "full" + std::to_string(target.index) + ".pcd";
      p.truth = target.world_lidar.inverse() * source.world_lidar;
      p.dist = p.truth.topRightCorner<3, 1>().norm();
      const int bin = derivedBin(p.dist);
      if (std::abs(source.index - target.index) < kDerivedMinGap || bin < 0 ||
          taken.count({p.source, p.target}))
        continue;
      const double cosine = (p.truth.topLeftCorner<3, 3>().trace() - 1.0) / 2.0;
      p.rel_rot = std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / EIGEN_PI;
      p.overlap = std::numeric_limits<double>::quiet_NaN();
      ++count.candidates[bin];
      candidates.push_back(p);
    }
  std::mt19937 rng(seed);
  fisherYates(candidates, rng);
  for (const RevisitPair& p : candidates) {
    const int bin = derivedBin(p.dist);
    if (count.chosen[bin] >= per_bin || taken.count({p.source, p.target}))
      continue;
    ++count.chosen[bin];
    taken.insert({p.target, p.source});
    chosen.push_back(p);
  }
  if (counts)
    *counts = count;
  return chosen;
}

/** \brief The scan index i of a file name "full<i>.pcd" (any folder), or -1. */
inline int scanIndex(const std::string& name)
{
  const std::string file = std::filesystem::path(name).filename().string();
  if (file.size() < 9 || file.compare(0, 4, "full") != 0 ||
      file.compare(file.size() - 4, 4, ".pcd") != 0)
    return -1;
  const std::string digits = file.substr(4, file.size() - 8);
  if (digits.find_first_not_of("0123456789") != std::string::npos)
    return -1;
  return std::stoi(digits);
}

/** \brief The world pose of scan \a index in \a poses, or null. */
inline const ScanPose* findScanPose(const std::vector<ScanPose>& poses, int index)
{
  for (const ScanPose& p : poses)
    if (p.index == index)
      return &p;
  return nullptr;
}

/** \brief T_target_source of \a pair from odometry poses whose position drifted
 * linearly with the scan index: the corrected position of scan i is p_i - i \a drift
 * (world frame, meters per scan index), so the reference translation becomes
 * t - (i_source - i_target) R_target^T drift. \a pair.truth unchanged when a scan
 * index or pose is missing (false). */
inline bool correctDrift(RevisitPair& pair, const std::vector<ScanPose>& poses,
                         const Eigen::Vector3d& drift)
{
  const int i = scanIndex(pair.source), j = scanIndex(pair.target);
  const ScanPose* target = findScanPose(poses, j);
  if (i < 0 || !target)
    return false;
  const Eigen::Matrix3d R_target = target->world_lidar.topLeftCorner<3, 3>();
  pair.truth.topRightCorner<3, 1>() -= (i - j) * (R_target.transpose() * drift);
  return true;
}

/** \brief Least-squares linear drift (as correctDrift) of the odometry from the
 * translation errors of estimates: minimizes the sum over the pairs of |t_ref - (i -
 * j) R_target^T d - t_est|^2, d = sum (i - j) R_target (t_ref - t_est) / sum (i -
 * j)^2. \a estimates[k] is T_target_source of pairs[k]; zero without usable pairs. */
inline Eigen::Vector3d fitDrift(const std::vector<RevisitPair>& pairs,
                                const std::vector<Eigen::Matrix4d>& estimates,
                                const std::vector<ScanPose>& poses)
{
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double norm = 0.0;
  for (std::size_t k = 0; k < pairs.size() && k < estimates.size(); ++k) {
    const int i = scanIndex(pairs[k].source), j = scanIndex(pairs[k].target);
    const ScanPose* target = findScanPose(poses, j);
    if (i < 0 || !target)
      continue;
    const Eigen::Vector3d error =
        pairs[k].truth.topRightCorner<3, 1>() - estimates[k].topRightCorner<3, 1>();
    sum += (i - j) * (target->world_lidar.topLeftCorner<3, 3>() * error);
    norm += static_cast<double>(i - j) * (i - j);
  }
  return norm > 0.0 ? Eigen::Vector3d(sum / norm) : Eigen::Vector3d::Zero();
}

} // namespace bench
} // namespace pcl::phaser
