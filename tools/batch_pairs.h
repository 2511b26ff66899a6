// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file batch_pairs.h
 * \brief The work of `pcl_phaser_batch`: pair lists, loop-closure candidates from a
 * trajectory, the order that prepares each target once, and shards.
 */
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace pcl {
namespace phaser {
namespace batch {

/** \brief One registration to run: T_target_source of \a source onto \a target. */
struct Pair {
  std::size_t index = 0;   ///< position in the whole list, from 0 (shard-independent)
  std::string source;      ///< the source as given in the list
  std::string target;      ///< the target as given in the list
  std::string source_path; ///< \a source resolved against the list's folder
  std::string target_path; ///< \a target resolved against the list's folder
  int source_id = 0;       ///< the source's vertex id (see PairList::names)
  int target_id = 0;       ///< the target's vertex id
  /** \brief Initial guess of T_target_source; identity when the line has none. */
  Eigen::Matrix4d guess = Eigen::Matrix4d::Identity();
  bool has_guess = false; ///< the line gave 12 numbers
};

/** \brief Every pair of a run and the clouds they name. */
struct PairList {
  std::vector<Pair> pairs;        ///< in list order; Pair::index is the position
  std::vector<std::string> names; ///< cloud names as given, by vertex id
  /** \brief T_world_cloud by vertex id, when the pairs came from a trajectory. */
  std::vector<Eigen::Matrix4d> poses;
};

/** \brief \a path made absolute against \a folder when it is relative. */
std::string resolvePath(const std::string& folder, const std::string& path);

/** \brief The folder of \a file ("." when it has none). */
std::string folderOf(const std::string& file);

/** \brief Read a pair list: one pair per line, `SOURCE TARGET` optionally followed by
 *  12 numbers (row-major 3x4 guess of T_target_source); `#` starts a comment; relative
 *  paths are taken against the list's folder. Vertex ids follow the order in which
 *  names first appear (source before target on a line).
 *  \param[in] path the list file
 *  \param[out] list the pairs (unspecified on failure)
 *  \return empty on success, else the reason, naming the file and the line */
std::string readPairList(const std::string& path, PairList& list);

/** \brief Read a scan list: one path per line (`#` comments, blank lines skipped),
 *  relative paths against the list's folder.
 *  \param[out] given the paths as written  \param[out] resolved the paths to open
 *  \return empty on success, else the reason */
std::string readScanList(const std::string& path, std::vector<std::string>& given,
                         std::vector<std::string>& resolved);

/** \brief Read poses: one row-major 3x4 T_world_scan per non-comment line, the last 12
 *  numbers of the line (KITTI's poses files and poses_T_world_lidar.txt both read).
 *  \return empty on success, else the reason */
std::string readPoses(const std::string& path, std::vector<Eigen::Matrix4d>& poses);

/** \brief Read a scan list and its poses (readScanList(), readPoses()), one pose per
 *  scan. \return empty on success, else the reason (a count that differs too) */
std::string readTrajectory(const std::string& scans, const std::string& poses_path,
                           std::vector<std::string>& given,
                           std::vector<std::string>& resolved,
                           std::vector<Eigen::Matrix4d>& poses);

/** \brief Loop-closure candidates: every pair of scans i < j with j - i >= \a min_gap
 *  whose positions lie within \a radius meters; the earlier scan is the target, so
 *  each measurement is T_i_j. Ids are the scans' positions in the list.
 *  \param[in] given scan names as written  \param[in] resolved their paths
 *  \param[in] poses T_world_scan, one per scan */
PairList makeCandidates(const std::vector<std::string>& given,
                        const std::vector<std::string>& resolved,
                        const std::vector<Eigen::Matrix4d>& poses, double radius,
                        int min_gap);

/** \brief The pairs in the `--pairs` format (paths as given, a guess only when set). */
std::string formatPairList(const PairList& list);

/** \brief Parse "K/N" with 0 <= K < N. \return the pair, or nothing when malformed */
std::optional<std::pair<int, int>> parseShard(const std::string& text);

/** \brief Indices into \a list.pairs of shard \a k of \a n: whole target groups where
 *  a group fits in an even share (larger groups are cut into shares first), dealt to
 *  the shard with the fewest pairs; every pair lands in exactly one shard, and the
 *  split depends only on the list. Within the shard, pairs come grouped by target
 *  (targets in order of first appearance) and in list order inside a group, so each
 *  target is prepared once. */
std::vector<std::size_t> shardPairs(const PairList& list, int k, int n);

} // namespace batch
} // namespace phaser
} // namespace pcl
