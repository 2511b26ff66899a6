// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file batch_cache.h
 * \brief Clouds loaded once and targets prepared once for `pcl_phaser_batch`: a
 * thread-safe cache of loaded cloud files shared by the jobs of a run, and each job's
 * least recently used prepared targets (the pcl::PhaserRegistration that keeps a
 * target's spectra).
 */
#pragma once

#include <pcl_phaser/phaser_registration.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace pcl {
namespace phaser {
namespace batch {

/** \brief One cloud file's finite points. */
struct CloudEntry {
  /** \brief The file has an intensity field (fused when both clouds have one, as in
   *  pcl_phaser_align). */
  bool intensity = false;
  pcl::PointCloud<pcl::PointXYZI>::Ptr with_intensity; ///< set when intensity
  pcl::PointCloud<pcl::PointXYZ>::Ptr xyz;             ///< always set
};

/** \brief Least recently used items by path, at most \a capacity of them. */
template <typename Item>
class LruCache {
public:
  explicit LruCache(std::size_t capacity)
      : capacity_(capacity < 1 ? 1 : capacity)
  {
  }
  /** \brief The item of \a path, moved to the front; null when absent. */
  std::shared_ptr<Item> find(const std::string& path)
  {
    const auto it = items_.find(path);
    if (it == items_.end())
      return nullptr;
    order_.splice(order_.begin(), order_, it->second.second);
    return it->second.first;
  }
  /** \brief Keep \a item for \a path, dropping the least recently used beyond the
   *  capacity. */
  void put(const std::string& path, std::shared_ptr<Item> item)
  {
    order_.push_front(path);
    items_[path] = {std::move(item), order_.begin()};
    while (items_.size() > capacity_) {
      items_.erase(order_.back());
      order_.pop_back();
    }
  }

private:
  std::size_t capacity_;
  std::list<std::string> order_; ///< most recently used first
  std::map<std::string,
           std::pair<std::shared_ptr<Item>, std::list<std::string>::iterator>>
      items_;
};

/** \brief Loaded clouds by path, shared by the jobs of a run (thread-safe). */
class CloudCache {
public:
  /** \param[in] capacity clouds kept, >= 1 */
  explicit CloudCache(std::size_t capacity)
      : clouds_(capacity)
  {
  }

  /** \brief The cloud of \a path, loaded when absent (through the tools' safe reader;
   *  non-finite points dropped). \param[out] error why it failed \return null on
   *  failure (missing, unreadable, no finite points) */
  std::shared_ptr<const CloudEntry> get(const std::string& path, std::string& error);

private:
  std::mutex mutex_;
  LruCache<const CloudEntry> clouds_;
};

/** \brief One target file prepared for each point type it was aligned with. */
struct PreparedTarget {
  std::shared_ptr<pcl::PhaserRegistration<pcl::PointXYZI, pcl::PointXYZI>>
      with_intensity;
  std::shared_ptr<pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ>> xyz;
};

/** \brief A job's prepared targets, least recently used out first (not shared). */
using PreparedTargets = LruCache<PreparedTarget>;

/** \brief Register \a source onto \a target (the cloud of \a target_path) with \a
 * params and \a guess, as pcl_phaser_align does (intensity fused when both have it),
 *  preparing the target on its first use in \a prepared and reusing it after. */
PhaserResult alignClouds(const CloudEntry& source, const std::string& target_path,
                         const CloudEntry& target, PreparedTargets& prepared,
                         const Eigen::Matrix4d& guess, const PhaserParameters& params);

} // namespace batch
} // namespace phaser
} // namespace pcl
