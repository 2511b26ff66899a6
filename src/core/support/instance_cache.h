/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <map>
#include <memory>
#include <mutex>

namespace pcl::phaser {
namespace detail {

/** \brief Process-wide cache of immutable objects keyed by their size parameters
 *  (tables and FFTW plans per bandwidth or grid size). Construction happens under the
 *  lock, so each key is built exactly once; the objects are then shared read-only. */
template <typename Key, typename T>
class InstanceCache {
public:
  template <typename Make>
  std::shared_ptr<const T> get(const Key& key, Make&& make)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = cache_.find(key);
    if (it != cache_.end())
      return it->second;
    std::shared_ptr<const T> value = make();
    cache_.emplace(key, value);
    return value;
  }

private:
  std::mutex mutex_;
  std::map<Key, std::shared_ptr<const T>> cache_;
};

} // namespace detail
} // namespace pcl::phaser
