/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>

#include <map>
#include <string>
#include <vector>

namespace pcl::phaser {
namespace bench {

/** \brief A prior map aggregated from balm_handheld scans and the scans left out of it.
 */
struct PriorMap {
  pcl::PointCloud<pcl::PointXYZI>::Ptr cloud;         ///< in the site frame
  Eigen::Matrix4d site = Eigen::Matrix4d::Identity(); ///< site <- scan 0's frame
  std::map<int, Eigen::Matrix4d> world_lidar; ///< T_world_lidar of every scan, by index
  std::vector<int> in_map, queries;           ///< scan indices
};

/** \brief A rigid move to a site frame whose origin lies \a distance meters from scan
 *  0's (0.5 rad from x, 7.5 m up), turned \a yaw_deg about z; the identity (scan 0's
 *  frame) when \a distance is 0. */
Eigen::Matrix4d siteFrame(double distance, double yaw_deg = 35.0);

/** \brief Reads `DIR/poses_T_world_lidar.txt` and every \a every -th listed scan
 *  `DIR/full<i>.pcd` from the first (the others are the queries), moved by \a site *
 *  T_world_lidar and, when \a voxel > 0, thinned to one point (centroid, mean
 *  intensity) per \a voxel cube of scan 0's frame. False with \a error when a file
 *  cannot be read. */
bool buildPriorMap(const std::string& dir, int every, double voxel,
                   const Eigen::Matrix4d& site, PriorMap& map, std::string& error);

/** \brief `DIR/full<index>.pcd`, non-finite points removed; null with \a error if it
 *  cannot be read. */
pcl::PointCloud<pcl::PointXYZI>::Ptr readScan(const std::string& dir, int index,
                                              std::string& error);

} // namespace bench
} // namespace pcl::phaser
