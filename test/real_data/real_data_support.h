/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Loading the shared scans in the real-data tests.
 */
#pragma once

#include "../registration/test_data.h"
#include "cloud_reading.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/filters/filter.h>
#include <pcl/point_cloud.h>

#include <gtest/gtest.h>

#include <string>

namespace pcl::phaser {
namespace test {

/** \brief A file of the shared data as PointT, NaN points removed (a test failure, and
 *  an empty cloud, when it cannot be read).
 *  \param[in] relative path inside the data directory */
template <typename PointT>
typename pcl::PointCloud<PointT>::Ptr loadFiniteCloud(const std::string& relative)
{
  auto cloud = pcl::make_shared<pcl::PointCloud<PointT>>();
  std::string error;
  if (!pcl::phaser::loadCloud(dataPath(relative), *cloud, &error))
    ADD_FAILURE() << error;
  pcl::Indices kept;
  pcl::removeNaNFromPointCloud(*cloud, *cloud, kept);
  return cloud;
}

/** \brief One align of \a source onto \a target with defaults and 2 threads: what it
 *  found (PhaserRegistration::getResult()). */
template <typename PointT>
pcl::phaser::PhaserResult
alignWithDefaults(const typename pcl::PointCloud<PointT>::ConstPtr& source,
                  const typename pcl::PointCloud<PointT>::ConstPtr& target)
{
  pcl::PhaserRegistration<PointT, PointT> phaser;
  phaser.setNumberOfThreads(2);
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  pcl::PointCloud<PointT> aligned;
  phaser.align(aligned);
  return phaser.getResult();
}

} // namespace test
} // namespace pcl::phaser
