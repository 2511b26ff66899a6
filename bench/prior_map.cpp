/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Prior maps aggregated from the balm_handheld scans, in any site frame.
 */
#include "prior_map.h"
#include "revisits.h"

#include <pcl/filters/filter.h>
#include <pcl/io/pcd_io.h>

#include <Eigen/Geometry>

#include <cmath>
#include <unordered_map>
#include <utility>

namespace pcl::phaser {
namespace bench {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZI>;

/** Points (x, y, z, intensity) summed per voxel, in first-seen order. */
class VoxelSums {
public:
  explicit VoxelSums(double voxel)
      : voxel_(voxel)
  {
  }
  void add(const Eigen::Vector3d& q, float intensity)
  {
    const Eigen::Array3d cell = (q / voxel_).array().floor() + (1 << 20);
    const long long key = (static_cast<long long>(cell.x()) << 42) |
                          (static_cast<long long>(cell.y()) << 21) |
                          static_cast<long long>(cell.z());
    auto [it, added] = cells_.try_emplace(key, Eigen::Vector4d::Zero(), 0);
    if (added)
      order_.push_back(key);
    it->second.first += Eigen::Vector4d(q.x(), q.y(), q.z(), intensity);
    ++it->second.second;
  }
  /** The means, in first-seen order. */
  std::vector<Eigen::Vector4d> means() const
  {
    std::vector<Eigen::Vector4d> out;
    for (long long key : order_) {
      const auto& cell = cells_.at(key);
      out.push_back(cell.first / cell.second);
    }
    return out;
  }

private:
  double voxel_;
  std::unordered_map<long long, std::pair<Eigen::Vector4d, int>> cells_;
  std::vector<long long> order_;
};

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
  VoxelSums sums(voxel > 0.0 ? voxel : 1.0);
  std::vector<Eigen::Vector4d> points;
  for (int i : map.in_map) {
    const Cloud::Ptr scan = readScan(dir, i, error);
    if (!scan)
      return false;
    const Eigen::Matrix4d& T = map.world_lidar[i];
    for (const pcl::PointXYZI& p : *scan) {
      const Eigen::Vector3d q =
          T.topLeftCorner<3, 3>() * p.getVector3fMap().cast<double>() +
          T.topRightCorner<3, 1>();
      if (voxel > 0.0)
        sums.add(q, p.intensity);
      else
        points.emplace_back(q.x(), q.y(), q.z(), p.intensity);
    }
  }
  if (voxel > 0.0)
    points = sums.means();
  map.cloud = pcl::make_shared<Cloud>();
  map.cloud->reserve(points.size());
  for (const Eigen::Vector4d& m : points) {
    pcl::PointXYZI p;
    p.getVector3fMap() =
        (site.topLeftCorner<3, 3>() * m.head<3>() + site.topRightCorner<3, 1>())
            .cast<float>();
    p.intensity = static_cast<float>(m.w());
    map.cloud->push_back(p);
  }
  return true;
}

} // namespace bench
} // namespace pcl::phaser
