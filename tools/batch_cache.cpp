// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
#include "batch_cache.h"
#include "cloud_reading.h"
#include "pcl_phaser_align_steps.h"

#include <pcl/common/io.h>
#include <pcl/point_types.h>

namespace pcl {
namespace phaser {
namespace batch {
namespace {

std::shared_ptr<CloudEntry> loadEntry(const std::string& path, std::string& error)
{
  pcl::PCLPointCloud2 blob;
  if (!pcl::phaser::loadCloud(path, blob, &error))
    return nullptr;
  for (const char* axis : {"x", "y", "z"})
    if (!align_tool::isFloatField(blob, pcl::getFieldIndex(blob, axis))) {
      error = "'" + path + "' has no float32/float64 " + axis + " field";
      return nullptr;
    }
  // The clouds as pcl::PhaserRegistration<PointXYZI> sees them: finite x, y, z and the
  // intensity, each a float.
  const auto cloud = align_tool::toFiniteCloud<pcl::PointXYZI>(blob);
  auto entry = std::make_shared<CloudEntry>();
  entry->points.resize(3, static_cast<Eigen::Index>(cloud->size()));
  if (pcl::getFieldIndex(blob, "intensity") >= 0)
    entry->intensity.resize(entry->points.cols());
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    const pcl::PointXYZI& p = (*cloud)[i];
    entry->points.col(static_cast<Eigen::Index>(i)) = Eigen::Vector3d(p.x, p.y, p.z);
    if (entry->hasIntensity())
      entry->intensity[static_cast<Eigen::Index>(i)] = p.intensity;
  }
  if (entry->points.cols() == 0) {
    error = "'" + path + "' has no finite points";
    return nullptr;
  }
  return entry;
}

/** \brief \a entry's points, and its intensity as the one channel when \a fused. */
ChannelValues channelsOf(const CloudEntry& entry, bool fused)
{
  return fused ? ChannelValues{entry.intensity} : ChannelValues{};
}

} // namespace

std::shared_ptr<const CloudEntry> CloudCache::get(const std::string& path,
                                                  std::string& error)
{
  const std::lock_guard<std::mutex> lock(mutex_);
  if (std::shared_ptr<const CloudEntry> entry = clouds_.find(path))
    return entry;
  std::shared_ptr<const CloudEntry> entry = loadEntry(path, error);
  if (entry)
    clouds_.put(path, entry);
  return entry;
}

PhaserResult alignClouds(const CloudEntry& source, const std::string& target_path,
                         const CloudEntry& target, PreparedTargets& prepared,
                         const Eigen::Matrix4d& guess, const PhaserParameters& params)
{
  std::shared_ptr<PreparedTarget> kept = prepared.find(target_path);
  if (!kept) {
    kept = std::make_shared<PreparedTarget>();
    prepared.put(target_path, kept);
  }
  const bool fused = source.hasIntensity() && target.hasIntensity() &&
                     (params.channels & CHANNEL_INTENSITY) != 0;
  std::shared_ptr<const Target>& model = fused ? kept->with_intensity : kept->xyz;
  if (!model)
    model = std::make_shared<const Target>(target.points, channelsOf(target, fused));
  SourceCloud cloud{source.points, channelsOf(source, fused)};
  return align(*model, cloud, guess, params);
}

} // namespace batch
} // namespace phaser
} // namespace pcl
