/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Prior maps aggregated from the balm_handheld scans, in any site frame.
 */
#include "map_builder.h"
#include "prior_map.h"
#include "revisits.h"

#include <pcl/filters/filter.h>
#include <pcl/io/pcd_io.h>

#include <Eigen/Geometry>

#include <cmath>

namespace pcl::phaser {
namespace bench {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZI>;

} // namespace

Eigen::Matrix4d siteFrame(double distance, double yaw_deg)
{
  Eigen::Matrix4d G = Eigen::Matrix4d::Identity();
  if (!(distance > 0.0))
    return G;
  G.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
  G.topRightCorner<3, 1>() =
      distance * Eigen::Vector3d(std::cos(0.5), std::sin(0.5), 0.0) +
      Eigen::Vector3d(0.0, 0.0, 7.5);
  return G;
}

Cloud::Ptr readScan(const std::string& dir, int index, std::string& error)
{
  auto cloud = pcl::make_shared<Cloud>();
  const std::string path = dir + "/full" + std::to_string(index) + ".pcd";
  if (pcl::io::loadPCDFile(path, *cloud) < 0) {
    error = "cannot read " + path;
    return nullptr;
  }
  pcl::Indices kept;
  pcl::removeNaNFromPointCloud(*cloud, *cloud, kept);
  return cloud;
}

bool buildPriorMap(const std::string& dir, int every, double voxel,
                   const Eigen::Matrix4d& site, PriorMap& map, std::string& error)
{
  std::vector<ScanPose> poses;
  if (!readScanPoses(dir + "/poses_T_world_lidar.txt", poses, error))
    return false;
  map = PriorMap();
  map.site = site;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    map.world_lidar[poses[k].index] = poses[k].world_lidar;
    (k % static_cast<std::size_t>(every) == 0 ? map.in_map : map.queries)
        .push_back(poses[k].index);
  }
  // Thinned in scan 0's frame, so every site frame holds the same points.
  MapBuilder builder(voxel);
  for (int i : map.in_map) {
    const Cloud::Ptr scan = readScan(dir, i, error);
    if (!scan)
      return false;
    builder.add(*scan, map.world_lidar[i]);
  }
  map.cloud = builder.cloud(site);
  return true;
}

} // namespace bench
} // namespace pcl::phaser
