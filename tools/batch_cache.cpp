// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
#include "batch_cache.h"
#include "cloud_reading.h"
#include "pcl_phaser_align_steps.h"

#include <pcl/common/io.h>

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
  auto entry = std::make_shared<CloudEntry>();
  entry->intensity = pcl::getFieldIndex(blob, "intensity") >= 0;
  entry->xyz = align_tool::toFiniteCloud<pcl::PointXYZ>(blob);
  if (entry->intensity)
    entry->with_intensity = align_tool::toFiniteCloud<pcl::PointXYZI>(blob);
  if (entry->xyz->empty()) {
    error = "'" + path + "' has no finite points";
    return nullptr;
  }
  return entry;
}

/** \brief Align with the registration kept in \a prepared (made on first use). */
template <typename PointT>
PhaserResult
alignWith(std::shared_ptr<pcl::PhaserRegistration<PointT, PointT>>& prepared,
          const typename pcl::PointCloud<PointT>::Ptr& source,
          const typename pcl::PointCloud<PointT>::Ptr& target,
          const Eigen::Matrix4d& guess, const PhaserParameters& params)
{
  if (!prepared) {
    prepared = std::make_shared<pcl::PhaserRegistration<PointT, PointT>>();
    prepared->setInputTarget(target);
  }
  prepared->setParameters(params);
  prepared->setInputSource(source);
  pcl::PointCloud<PointT> aligned;
  prepared->align(aligned, guess.cast<float>());
  return prepared->getResult();
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
  if (source.intensity && target.intensity)
    return alignWith<pcl::PointXYZI>(kept->with_intensity, source.with_intensity,
                                     target.with_intensity, guess, params);
  return alignWith<pcl::PointXYZ>(kept->xyz, source.xyz, target.xyz, guess, params);
}

} // namespace batch
} // namespace phaser
} // namespace pcl
