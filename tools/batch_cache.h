// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file batch_cache.h
 * \brief Clouds loaded once and targets prepared once for `pcl_phaser_batch`: a
 * thread-safe cache of loaded cloud files shared by the jobs of a run, and each job's
 * least recently used prepared targets (pcl::phaser::Target, which keeps a target's
 * spectra).
 */
#pragma once

#include <pcl_phaser/core/pipeline.h>
#include <pcl_phaser/point_channels.h>

#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace pcl {
namespace phaser {
namespace batch {

/** \brief One cloud file's finite points (3 x n, the file's float values). */
struct CloudEntry {
  Eigen::Matrix3Xd points;
  /** \brief Per point, when the file has an intensity field (empty otherwise): fused
   *  when both clouds have one, as in pcl_phaser_align. */
  Eigen::VectorXd intensity;
  bool hasIntensity() const { return intensity.size() != 0; }
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

/** \brief One target file prepared with its intensity and without (each made when a
 *  source first needs it). */
struct PreparedTarget {
  std::shared_ptr<const Target> with_intensity, xyz;
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
