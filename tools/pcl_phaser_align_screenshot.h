// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file pcl_phaser_align_screenshot.h
 * \brief Headless PNG rendering of the `pcl_phaser_align` overlay with
 * pcl::visualization::PCLVisualizer (off-screen render window; needs an X server,
 * e.g. Xvfb), in a module the tool opens on first use (pcl_phaser_align_screenshot.cpp);
 * both functions refuse with the reason when PCL's visualization was not found at build
 * time or the module cannot be loaded.
 */
#pragma once

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <string>

namespace pcl {
namespace phaser {

/** \brief Whether saveOverlayScreenshot() can work here: the tool was built with
 * pcl_visualization and an X display is set and answers. Without this check VTK
 * aborts the process when it cannot reach an X server.
 * \param[out] reason why not, when false is returned
 * \return true if a screenshot can be taken
 */
bool canSaveScreenshot(std::string& reason);

/** \brief Render a colored cloud top-down (the camera looks down -z and is fitted to
 * the cloud) on a white background and save it as a PNG of exactly width x height.
 * \param[in] cloud the cloud, colored by its rgb field
 * \param[in] path the PNG file to write
 * \param[in] width,height image size in pixels
 * \param[out] error the reason, when false is returned
 * \return true if a non-empty file was written
 */
bool saveOverlayScreenshot(const pcl::PointCloud<pcl::PointXYZRGB>::ConstPtr& cloud,
                           const std::string& path, int width, int height,
                           std::string& error);

} // namespace phaser
} // namespace pcl
