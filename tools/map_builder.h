/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * A prior map aggregated from scans and their poses, thinned per voxel.
 */
#pragma once

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>

#include <functional>
#include <unordered_map>
#include <utility>
#include <vector>

namespace pcl {
namespace phaser {

/** \brief Scans added in a world frame, kept as one point per \a voxel cube (the mean
 *  position and intensity of the points in it, cubes in first-seen order) or, with
 *  voxel 0, every point. A map thinned to the finest cell the target model uses is
 *  what a region query prepares anyway (doc/benchmarks.md, *Position prior*). */
class MapBuilder {
public:
  /** \param[in] voxel edge of the thinning cubes, meters; 0: no thinning */
  explicit MapBuilder(double voxel)
      : voxel_(voxel)
  {
  }
  /** \brief Add \a scan's finite points moved by \a world_scan (T_world_scan); points
   *  whose cube index would not fit 62 bits are kept unthinned. */
  void add(const pcl::PointCloud<pcl::PointXYZI>& scan,
           const Eigen::Matrix4d& world_scan);
  /** \brief The map, each point moved by \a site (default: the world frame). */
  pcl::PointCloud<pcl::PointXYZI>::Ptr
  cloud(const Eigen::Matrix4d& site = Eigen::Matrix4d::Identity()) const;

private:
  /** A cube's integer coordinates. */
  struct Cell {
    long long x, y, z;
    bool operator==(const Cell& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct CellHash {
    std::size_t operator()(const Cell& c) const
    {
      return std::hash<long long>()(c.x * 73856093LL ^ c.y * 19349663LL ^
                                    c.z * 83492791LL);
    }
  };
  double voxel_;
  std::unordered_map<Cell, std::pair<Eigen::Vector4d, int>, CellHash> cells_;
  std::vector<Cell> order_;
  std::vector<Eigen::Vector4d> points_; ///< with voxel 0
};

} // namespace phaser
} // namespace pcl
