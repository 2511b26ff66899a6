// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file batch_records.h
 * \brief The outputs of `pcl_phaser_batch`: one JSON record per pair in a JSONL file
 * that survives being killed at any moment, and the g2o pose graph made from them.
 */
#pragma once

#include "batch_pairs.h"
#include "result_json.h"

#include <pcl_phaser/core/pipeline.h>

#include <Eigen/Core>

#include <optional>
#include <set>
#include <string>
#include <vector>

namespace pcl {
namespace phaser {
namespace batch {

/** \brief One record: members keep the order they are written in. */
using Record = JsonObject;

/** \brief The record of a pair that was aligned: pair, pairs, source, target,
 *  source_id, target_id, status "ok", transformation (4x4 row-major), converged, the
 *  fields of visitResultFields() (core/result.h, as `pcl_phaser_align --json` writes
 *  them) and time_ms. Numbers round-trip exactly. */
Record alignedRecord(const Pair& pair, std::size_t pairs, const PhaserResult& result,
                     double time_ms);

/** \brief The record of a pair that could not be aligned: status "failed" and why. */
Record failedRecord(const Pair& pair, std::size_t pairs, const std::string& reason);

/** \brief What makes records of one run comparable, the "run" of every record: shard
 *  \a shard of \a shards and the settings of \a p that change results (not threads),
 *  e.g. "shard 0/1, B 64, grid 128, voxel 0, passes 3, auto"; a setting beyond those
 *  is added (", whitening 0.25") only when it is not at its default, so records of an
 *  earlier version keep theirs. */
std::string runFingerprint(const PhaserParameters& p, int shard, int shards);

/** \brief The key that identifies a pair in records: source and target as given. */
std::string pairKey(const std::string& source, const std::string& target);

/** \brief Read a JSONL file of records. With \a repair, a last line cut short by a
 *  kill (no newline at the end, or not JSON) is cut off the file, so appending goes
 *  on from the last whole record; any other bad line is an error.
 *  \param[in] path the file (a missing file reads as no records)
 *  \param[out] records the records, in file order
 *  \return empty on success, else the reason */
std::string readRecords(const std::string& path, std::vector<Record>& records,
                        bool repair);

/** \brief Appends records to a JSONL file, each line in one write() and synced to the
 *  disk before the next pair starts. */
class RecordWriter {
public:
  /** \brief Open \a path for appending (created when missing). \return the reason on
   *  failure, else empty */
  std::string open(const std::string& path);
  /** \brief Append \a record as one line. \return the reason on failure, else empty */
  std::string append(const Record& record);
  ~RecordWriter();

private:
  int fd_ = -1;
  std::string path_;
};

/** \brief The information matrix of a g2o EDGE_SE3:QUAT for measurement \a T
 *  (T_target_source) and \a covariance (getCovariance()'s order and frames): g2o's
 *  error is (translation, quaternion x y z) of T^-1 T_true, so (omega, nu) of the
 *  target frame map to (R^T nu, R^T omega / 2). */
Eigen::Matrix<double, 6, 6>
g2oInformation(const Eigen::Matrix4d& T, const Eigen::Matrix<double, 6, 6>& covariance);

/** \brief The measurement \a T (T_target_source) and \a covariance of a converged
 *  record. \return false for any other record */
bool convergedEdge(const Record& record, Eigen::Matrix4d& T,
                   Eigen::Matrix<double, 6, 6>& covariance);

/** \brief `EDGE_SE3:QUAT i j x y z qx qy qz qw` and the 21 upper-triangular entries of
 *  the information, for a converged record; empty for any other. */
std::string g2oEdge(const Record& record);

/** \brief `VERTEX_SE3:QUAT id x y z qx qy qz qw` of \a pose. */
std::string g2oVertex(int id, const Eigen::Matrix4d& pose);

/** \brief Write a file whole or not at all: a temporary beside it, synced, renamed.
 *  \return the reason on failure, else empty */
std::string writeFileAtomically(const std::string& path, const std::string& text);

/** \brief Standard deviations of one odometry edge (between consecutive scans). */
struct OdometrySigma {
  double translation = 0.05; ///< meters, per axis
  double rotation_deg = 0.5; ///< degrees, about each axis
};

/** \brief `EDGE_SE3:QUAT i i+1` measuring T_world_i^-1 T_world_i+1 (\a from, \a to)
 *  with the information of \a sigma in g2o's error (translation, quaternion x y z =
 *  half the rotation vector): diag(1 / s_t^2, 4 / s_r^2). */
std::string g2oOdometryEdge(int i, const Eigen::Matrix4d& from,
                            const Eigen::Matrix4d& to, const OdometrySigma& sigma);

/** \brief The g2o graph of \a records (edges of converged pairs, sorted by target and
 *  source id) with a vertex per pose of \a poses; with \a odometry also `FIX 0` and an
 *  odometry edge between consecutive poses (a loop edge of the same pair replaces it),
 *  a complete pose graph. */
std::string g2oGraph(const std::vector<Record>& records,
                     const std::vector<Eigen::Matrix4d>& poses,
                     const std::optional<OdometrySigma>& odometry = std::nullopt);

/** \brief Join shard outputs into \a out: JSONL parts (sorted by pair index; every
 *  index of the list exactly once) or g2o parts (vertices agreeing, each edge once),
 *  chosen by \a out's extension. \return the reason on failure, else empty */
std::string mergeParts(const std::string& out, const std::vector<std::string>& parts);

} // namespace batch
} // namespace phaser
} // namespace pcl
