// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file icp_module.cpp
 * \brief The module behind `pcl_phaser_align -icp` (pcl_phaser_align_icp.h): only it
 * links PCL's features and registration, and the tool loads it when -icp is given. Its
 * entry points have C names, so the loader finds them with dlsym.
 */
#include "icp_refinement.h"

namespace align = pcl::phaser::align_tool;

extern "C" void pcl_phaser_icp_refine_xyz(
    const pcl::PointCloud<pcl::PointXYZ>::Ptr& source,
    const pcl::PointCloud<pcl::PointXYZ>::Ptr& target, const Eigen::Matrix4d& guess,
    const align::IcpSettings& settings, align::Stage& s, align::IcpRun& run)
{
  align::refine<pcl::PointXYZ>(source, target, guess, settings, s, run);
}

extern "C" void pcl_phaser_icp_refine_xyzi(
    const pcl::PointCloud<pcl::PointXYZI>::Ptr& source,
    const pcl::PointCloud<pcl::PointXYZI>::Ptr& target, const Eigen::Matrix4d& guess,
    const align::IcpSettings& settings, align::Stage& s, align::IcpRun& run)
{
  align::refine<pcl::PointXYZI>(source, target, guess, settings, s, run);
}
