/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <utility>
#include <vector>

namespace pcl::phaser {

/** \brief Points grouped by the cubic voxel that holds them: the groups in increasing
 *  order of their voxel key, and within a group the points in input order, so every
 *  use is deterministic. Points that are not finite or lie beyond 2^20 voxels of the
 *  origin are left out. */
struct VoxelGroups {
  double voxel_size = 1.0;        ///< edge of a voxel, meters
  std::vector<std::int64_t> keys; ///< one per group, increasing
  std::vector<Eigen::Index>
      offsets;                     ///< group g holds order[offsets[g], offsets[g + 1])
  std::vector<Eigen::Index> order; ///< point indices, grouped
  std::size_t size() const { return keys.size(); }
};

/** \brief Key of the voxel of edge \a voxel_size that holds \a p (the keys of
 *  VoxelGroups); false when \a p is not finite or out of range. */
bool voxelKey(const Eigen::Vector3d& p, double voxel_size, std::int64_t& key);

/** \brief Groups \a points (3 x n) by voxels of edge \a voxel_size (> 0). */
VoxelGroups groupByVoxel(const Eigen::Matrix3Xd& points, double voxel_size);

/** \brief The centroid of every voxel of edge \a voxel_size that holds at least
 *  \a min_points points: a cloud of even density (one sample per occupied voxel). */
Eigen::Matrix3Xd voxelCentroids(const Eigen::Matrix3Xd& points, double voxel_size,
                                int min_points = 1);

/** \brief Fixed-radius nearest-point queries on a point set: cells of edge radius;
 *  a query reads the 27 cells around it. */
class PointIndex {
public:
  PointIndex() = default;
  /** \param[in] points 3 x n (copied) \param[in] radius query radius in meters (> 0)
   *  \param[in] normals optional unit normal per point (3 x n; zero: none) */
  PointIndex(const Eigen::Matrix3Xd& points, double radius,
             const Eigen::Matrix3Xd& normals = Eigen::Matrix3Xd());
  /** \brief Squared distance from \a q to its nearest point within radius(), else
   *  +infinity, among the points whose normal agrees with \a normal (dot product >=
   *  \a min_cosine) or that have none; a zero \a normal accepts every point. */
  double nearestSquaredDistance(const Eigen::Vector3d& q, const Eigen::Vector3d& normal,
                                double min_cosine) const;
  /** \brief Index of the nearest point within radius() to \a q among those whose
   *  normal agrees with \a normal (as nearestSquaredDistance), or -1 when none. */
  Eigen::Index nearest(const Eigen::Vector3d& q, const Eigen::Vector3d& normal,
                       double min_cosine) const;
  /** \brief Point \a k (0 <= k < size()), in the index's own order. */
  Eigen::Vector3d point(Eigen::Index k) const { return points_.col(k); }
  /** \brief Normal of point \a k: zero when the index has none. */
  Eigen::Vector3d normal(Eigen::Index k) const
  {
    return normals_.cols() != 0 ? Eigen::Vector3d(normals_.col(k))
                                : Eigen::Vector3d::Zero();
  }
  double radius() const { return radius_; }
  bool empty() const { return points_.cols() == 0; }

private:
  /** Key of a free slot: voxel keys are never negative. */
  static constexpr std::int64_t kEmptyKey = -1;
  /** A cell of the table: its voxel key, its points [first, last) in points_, and which
   *  of the 27 cells around it (itself included) hold points: bit
   *  (dx + 1) * 9 + (dy + 1) * 3 + (dz + 1). The table holds every cell with points and
   *  every cell next to one. */
  struct Cell {
    std::int64_t key = kEmptyKey;
    Eigen::Index first = 0, last = 0;
    std::uint32_t occupied = 0;
  };
  /** Most cells of the directory's box (16 MB of indices): a cloud's cells within it
   *  are looked up by position, beyond it by hash. */
  static constexpr double kMaxDirectoryCells = 4.0 * (1 << 20);
  /** Moves the table's cells into cells_, in key order, with directory_ their index at
   *  every position of their bounding box, when that box is at most
   *  kMaxDirectoryCells; else keeps the hash table. */
  void buildDirectory();
  /** The three biased axis indices of \a key (x first). */
  static Eigen::Array3i keyAxes(std::int64_t key);
  /** Position of the axis indices \a axes (inside the box) in directory_. */
  std::size_t directoryIndex(const Eigen::Array3i& axes) const;
  /** First slot of \a key's probe sequence. */
  std::size_t slotOf(std::int64_t key) const;
  /** The cell of \a key, or nullptr when the table has none. */
  const Cell* find(std::int64_t key) const;
  /** The slot of \a key, added (without points) when absent; grows the table to keep it
   *  at most a quarter full. */
  std::size_t insert(std::int64_t key);
  /** The nearest point of \a cell to \a q closer than \a best (squared, updated) with
   *  an agreeing normal, into \a found. */
  void scanCell(const Cell& cell, const Eigen::Vector3d& q,
                const Eigen::Vector3d& normal, double min_cosine, double& best,
                Eigen::Index& found) const;

  /** Points and normals one row per axis (row-major): a cell's coordinates are
   *  contiguous per axis, so scanCell's distances vectorize. */
  using Rows = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor>;
  double radius_ = 0.0;
  Rows points_;
  Rows normals_;                 ///< empty, or one per point
  std::vector<char> has_normal_; ///< per point: its normal is not zero
  std::vector<Cell> slots_;      ///< a power of two of them, at most a quarter used
  /** The table's cells by key, and per position of their bounding box (low corner,
   *  dims) the index of its cell or -1: a look-up reads nearby memory, where the hash
   *  table's slots scatter (the probes were half of nearest()'s time). Empty: the hash
   *  table serves. */
  std::vector<Cell> cells_;
  std::vector<std::int32_t> directory_;
  Eigen::Array3i directory_low_ = Eigen::Array3i::Zero();
  Eigen::Array3i directory_dims_ = Eigen::Array3i::Zero();
  std::size_t used_ = 0; ///< slots holding a cell
  int slot_shift_ = 60;  ///< 64 - log2(slots_.size())
};

} // namespace pcl::phaser
