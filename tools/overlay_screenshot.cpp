// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file overlay_screenshot.cpp
 * \brief The module behind `pcl_phaser_align --screenshot` (see
 * pcl_phaser_align_screenshot.h): only it links PCL's visualization, VTK and X11, and
 * the tool loads it when a screenshot is asked for. Its two entry points have C names
 * (kScreenshotCheck, kScreenshotSave), so the loader finds them with dlsym.
 */
#include "pcl_phaser_align_screenshot.h"

#include <pcl/common/common.h>
#include <pcl/visualization/pcl_visualizer.h>

#include <vtkRenderWindow.h>
#ifdef PCL_PHASER_ALIGN_HAVE_X11
#include <X11/Xlib.h>
#endif

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <thread>

namespace pcl {
namespace phaser {

#ifdef PCL_PHASER_ALIGN_HAVE_X11
namespace {
/** \brief An X connection opened by the first check and held until the process ends.
 * An X server started without -noreset (xvfb-run's) resets whenever its last client
 * leaves and refuses connections meanwhile, which VTK answers with abort(): holding
 * one connection keeps the server up from the check to the rendering. A refused
 * connection is retried for up to 2 s, in case the server is resetting right now. */
Display* heldConnection()
{
  static Display* connection = nullptr;
  for (int attempt = 0; !connection && attempt < 20; ++attempt) {
    if (attempt)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    connection = XOpenDisplay(nullptr);
  }
  return (connection);
}
} // namespace
#endif

namespace {

bool canSave(std::string& reason)
{
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display) {
    reason = "no X display: DISPLAY is not set. Rendering needs an X server; run "
             "headless as: xvfb-run -a -s \"-screen 0 1280x1024x24\" pcl_phaser_align "
             "ARGS";
    return (false);
  }
#ifdef PCL_PHASER_ALIGN_HAVE_X11
  // VTK aborts the process when the X server does not answer: ask first.
  if (!heldConnection()) {
    reason = std::string("cannot connect to the X display '") + display +
             "'; run headless under xvfb-run -a -s \"-screen 0 1280x1024x24\"";
    return (false);
  }
#endif
  return (true);
}

bool save(const pcl::PointCloud<pcl::PointXYZRGB>::ConstPtr& cloud,
          const std::string& path, int width, int height, std::string& error)
{
  if (!canSave(error))
    return (false);
  if (!cloud || cloud->empty()) {
    error = "nothing to render (empty overlay)";
    return (false);
  }
  // Keep the default interactor: without one, saveScreenshot() crashes in PCL 1.13.
  pcl::visualization::PCLVisualizer viz("pcl_phaser_align");
  viz.getRenderWindow()->SetOffScreenRendering(1);
  viz.setSize(width, height);
  viz.setBackgroundColor(1.0, 1.0, 1.0);
  pcl::visualization::PointCloudColorHandlerRGBField<pcl::PointXYZRGB> rgb(cloud);
  viz.addPointCloud<pcl::PointXYZRGB>(cloud, rgb, "overlay");
  viz.setPointCloudRenderingProperties(pcl::visualization::PCL_VISUALIZER_POINT_SIZE, 2,
                                       "overlay");
  // Top-down: look down -z at the center of the bounding box, y up; resetCamera()
  // keeps that direction and moves the camera back until everything is in view.
  pcl::PointXYZRGB lo, hi;
  pcl::getMinMax3D(*cloud, lo, hi);
  const double cx = 0.5 * (lo.x + hi.x), cy = 0.5 * (lo.y + hi.y);
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-3f});
  viz.setCameraPosition(cx, cy, hi.z + 2.0 * extent, cx, cy, lo.z, 0.0, 1.0, 0.0);
  viz.resetCamera();
  viz.spinOnce(1);
  std::error_code ec;
  std::filesystem::remove(path, ec);
  viz.saveScreenshot(path);
  if (std::filesystem::file_size(path, ec) == 0 || ec) {
    error = "the renderer wrote no image to " + path;
    return (false);
  }
  return (true);
}

} // namespace
} // namespace phaser
} // namespace pcl

extern "C" bool pcl_phaser_can_save_screenshot(std::string& reason)
{
  return (pcl::phaser::canSave(reason));
}

extern "C" bool pcl_phaser_save_overlay_screenshot(
    const pcl::PointCloud<pcl::PointXYZRGB>::ConstPtr& cloud, const std::string& path,
    int width, int height, std::string& error)
{
  return (pcl::phaser::save(cloud, path, width, height, error));
}
