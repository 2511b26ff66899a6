/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Explicit instantiations for PCL's common point types (source type = target type).
 * Other types: include <pcl_phaser/custom_point_types.h>.
 */
#include <pcl_phaser/impl/phaser_registration.hpp>
#include <pcl_phaser/phaser_registration.h>

#include <pcl/impl/instantiate.hpp>
#include <pcl/point_types.h>

#define PCL_INSTANTIATE_PhaserRegistration(T)                                          \
  template class pcl::PhaserRegistration<T, T>;

// clang-format off
PCL_INSTANTIATE(PhaserRegistration, (pcl::PointXYZ)(pcl::PointXYZI)(pcl::PointXYZRGB)
                                    (pcl::PointXYZRGBA)(pcl::PointNormal)(pcl::PointXYZINormal))
// clang-format on
