/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Prior maps aggregated from the shared handheld scans (lidar/balm_handheld), for the
 * prior-map benchmark and tests: scans in the world frame (scan 0's), every k-th in the
 * map, the others as queries. Header-only, like revisits.h.
 */
#pragma once

#include "cloud_reading.h"
#include "revisits.h"

#include <pcl_phaser/core/pipeline.h>

#include <pcl/filters/filter.h>
#include <pcl/point_types.h>

#include <memory>
#include <string>
#include <vector>

namespace pcl::phaser {
namespace bench {

/** \brief Scan full<index>.pcd of \a dir (points and intensity) moved by \a pose; empty
 *  with \a error when it cannot be read. */
inline SourceCloud loadScan(const std::string& dir, int index,
                            const Eigen::Matrix4d& pose, std::string& error)
{
  pcl::PointCloud<pcl::PointXYZI> cloud;
  SourceCloud out;
  if (!loadCloud(dir + "/full" + std::to_string(index) + ".pcd", cloud, &error))
    return out;
  pcl::Indices kept;
  pcl::removeNaNFromPointCloud(cloud, cloud, kept);
  out.points.resize(3, static_cast<Eigen::Index>(cloud.size()));
  out.channels.assign(1, Eigen::VectorXd(static_cast<Eigen::Index>(cloud.size())));
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector4d p(cloud[i].x, cloud[i].y, cloud[i].z, 1.0);
    out.points.col(i) = (pose * p).head<3>();
    out.channels[0](i) = cloud[i].intensity;
  }
  return out;
}

/** \brief A map of the scans whose index is a multiple of \a every, unthinned, moved by
 *  \a site (T_site_world), and the poses of all scans (T_world_lidar). */
struct PriorMap {
  std::vector<ScanPose> poses;
  std::unique_ptr<Target> map;
  std::string error; ///< empty when built
};

inline PriorMap buildPriorMap(const std::string& dir, int every,
                              const Eigen::Matrix4d& site = Eigen::Matrix4d::Identity())
{
  PriorMap m;
  if (!readScanPoses(dir + "/poses_T_world_lidar.txt", m.poses, m.error))
    return m;
  Eigen::Matrix3Xd points(3, 0);
  Eigen::VectorXd intensity(0);
  for (const ScanPose& pose : m.poses) {
    if (pose.index % every != 0)
      continue;
    const SourceCloud scan =
        loadScan(dir, pose.index, site * pose.world_lidar, m.error);
    if (!m.error.empty())
      return m;
    const Eigen::Index n = points.cols();
    points.conservativeResize(3, n + scan.points.cols());
    points.rightCols(scan.points.cols()) = scan.points;
    intensity.conservativeResize(n + scan.points.cols());
    intensity.tail(scan.points.cols()) = scan.channels[0];
  }
  m.map = std::make_unique<Target>(std::move(points), ChannelValues{intensity});
  return m;
}

/** \brief T_world_lidar of scan \a index, or null. */
inline const ScanPose* scanPose(const PriorMap& m, int index)
{
  for (const ScanPose& pose : m.poses)
    if (pose.index == index)
      return &pose;
  return nullptr;
}

} // namespace bench
} // namespace pcl::phaser
