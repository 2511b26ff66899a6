// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file batch_cache.h
 * \brief Clouds loaded once and targets prepared once for `pcl_phaser_batch`: a least
 * recently used cache of cloud files, each with the pcl::PhaserRegistration that
 * keeps its target spectra.
 */
#pragma once

#include <pcl_phaser/phaser_registration.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <list>
#include <map>
#include <memory>
#include <string>

namespace pcl {
namespace phaser {
namespace batch {

/** \brief One cloud file: its finite points and, once it served as a target, the
 *  registration that holds its prepared spectra. */
struct CloudEntry {
  /** \brief The file has an intensity field (fused when both clouds have one, as in
   *  pcl_phaser_align). */
  bool intensity = false;
  pcl::PointCloud<pcl::PointXYZI>::Ptr with_intensity; ///< set when intensity
  pcl::PointCloud<pcl::PointXYZ>::Ptr xyz;             ///< always set
  std::shared_ptr<pcl::PhaserRegistration<pcl::PointXYZI, pcl::PointXYZI>> target_i;
  std::shared_ptr<pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ>> target_xyz;
};

/** \brief Loaded clouds by path, at most a given number, least recently used out
 *  first. */
class CloudCache {
public:
  /** \param[in] capacity entries kept, >= 1 */
  explicit CloudCache(std::size_t capacity)
      : capacity_(capacity < 1 ? 1 : capacity)
  {
  }

  /** \brief The entry of \a path, loaded when absent (through the tools' safe reader;
   *  non-finite points dropped). \param[out] error why it failed \return null on
   *  failure (missing, unreadable, no finite points) */
  std::shared_ptr<CloudEntry> get(const std::string& path, std::string& error);

private:
  std::size_t capacity_;
  std::list<std::string> order_; ///< most recently used first
  std::map<std::string,
           std::pair<std::shared_ptr<CloudEntry>, std::list<std::string>::iterator>>
      entries_;
};

/** \brief What one align gave: the engine's result and getCovariance(). */
struct AlignOutcome {
  PhaserResult result;
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
};

/** \brief Register \a source onto \a target with \a params and \a guess, as
 *  pcl_phaser_align does (intensity fused when both have it), preparing \a target
 *  on its first use and reusing it after. */
AlignOutcome alignEntries(const CloudEntry& source, CloudEntry& target,
                          const Eigen::Matrix4d& guess, const PhaserParameters& params);

} // namespace batch
} // namespace phaser
} // namespace pcl
