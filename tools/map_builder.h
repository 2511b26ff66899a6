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
  /** \brief Add \a scan's finite points moved by \a world_scan (T_world_scan). */
  void add(const pcl::PointCloud<pcl::PointXYZI>& scan,
           const Eigen::Matrix4d& world_scan);
  /** \brief The map, each point moved by \a site (default: the world frame). */
  pcl::PointCloud<pcl::PointXYZI>::Ptr
  cloud(const Eigen::Matrix4d& site = Eigen::Matrix4d::Identity()) const;

private:
  double voxel_;
  std::unordered_map<long long, std::pair<Eigen::Vector4d, int>> cells_;
  std::vector<long long> order_;
  std::vector<Eigen::Vector4d> points_; ///< with voxel 0
};

} // namespace phaser
} // namespace pcl
