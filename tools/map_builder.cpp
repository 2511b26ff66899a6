/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "map_builder.h"

#include <cmath>

namespace pcl {
namespace phaser {

void MapBuilder::add(const pcl::PointCloud<pcl::PointXYZI>& scan,
                     const Eigen::Matrix4d& world_scan)
{
  for (const pcl::PointXYZI& p : scan) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      continue;
    const Eigen::Vector3d q =
        world_scan.topLeftCorner<3, 3>() * p.getVector3fMap().cast<double>() +
        world_scan.topRightCorner<3, 1>();
    const Eigen::Vector4d point(q.x(), q.y(), q.z(), p.intensity);
    const Eigen::Array3d cell = (q / voxel_).array().floor();
    if (!(voxel_ > 0.0) || !(cell.abs() < 4.0e18).all()) {
      points_.push_back(point);
      continue;
    }
    const Cell key{static_cast<long long>(cell.x()), static_cast<long long>(cell.y()),
                   static_cast<long long>(cell.z())};
    auto [it, added] = cells_.try_emplace(key, Eigen::Vector4d::Zero(), 0);
    if (added)
      order_.push_back(key);
    it->second.first += point;
    ++it->second.second;
  }
}

pcl::PointCloud<pcl::PointXYZI>::Ptr
MapBuilder::cloud(const Eigen::Matrix4d& site) const
{
  auto out = pcl::make_shared<pcl::PointCloud<pcl::PointXYZI>>();
  const auto put = [&](const Eigen::Vector4d& m) {
    pcl::PointXYZI p;
    p.getVector3fMap() =
        (site.topLeftCorner<3, 3>() * m.head<3>() + site.topRightCorner<3, 1>())
            .cast<float>();
    p.intensity = static_cast<float>(m.w());
    out->push_back(p);
  };
  for (const Eigen::Vector4d& m : points_)
    put(m);
  for (const Cell& key : order_) {
    const auto& cell = cells_.at(key);
    put(cell.first / cell.second);
  }
  return out;
}

} // namespace phaser
} // namespace pcl
