/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl/search/kdtree.h>

#include <atomic>
#include <mutex>
#include <vector>

namespace pcl {
namespace phaser {

/** \brief A pcl::search::KdTree that builds its index at the first search after
 *  setInputCloud(), not in it, so that align() does not pay for an index only
 *  getFitnessScore() uses. Concurrent searches are safe; setInputCloud() during one is
 *  not. */
template <typename PointT>
class LazyKdTree : public pcl::search::KdTree<PointT> {
public:
  using Base = pcl::search::KdTree<PointT>;
  using typename Base::IndicesConstPtr;
  using typename Base::PointCloudConstPtr;

  /** \brief Keep \a cloud (and \a indices) for the next search, which builds the index.
   *  \param[in] cloud the points to search \param[in] indices a subset, or null */
  void setInputCloud(const PointCloudConstPtr& cloud,
                     const IndicesConstPtr& indices = IndicesConstPtr()) override
  {
    std::lock_guard<std::mutex> lock(mutex_);
    this->input_ = cloud;
    this->indices_ = indices;
    built_.store(false, std::memory_order_release);
  }

  /** \brief Builds the index if needed, then searches. */
  int nearestKSearch(const PointT& point, int k, Indices& k_indices,
                     std::vector<float>& k_sqr_distances) const override
  {
    build();
    return Base::nearestKSearch(point, k, k_indices, k_sqr_distances);
  }

  /** \brief Builds the index if needed, then searches. */
  int radiusSearch(const PointT& point, double radius, Indices& k_indices,
                   std::vector<float>& k_sqr_distances,
                   unsigned int max_nn = 0) const override
  {
    build();
    return Base::radiusSearch(point, radius, k_indices, k_sqr_distances, max_nn);
  }

private:
  // The tree is never created const: the const_cast only lets a search fill its index.
  void build() const
  {
    if (built_.load(std::memory_order_acquire))
      return;
    std::lock_guard<std::mutex> lock(mutex_);
    if (built_.load(std::memory_order_relaxed) || !this->input_)
      return;
    auto* self = const_cast<LazyKdTree*>(this);
    self->Base::setInputCloud(this->input_, this->indices_);
    built_.store(true, std::memory_order_release);
  }

  mutable std::mutex mutex_;
  mutable std::atomic<bool> built_{false};
};

} // namespace phaser
} // namespace pcl
