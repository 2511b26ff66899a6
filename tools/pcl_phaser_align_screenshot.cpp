// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file pcl_phaser_align_screenshot.cpp
 * \brief The loader of the screenshot module (overlay_screenshot.cpp): the tool itself
 * does not link PCL's visualization, VTK or X11, whose 47 libraries cost every run a
 * tenth of a second of dynamic linking (122 libraries against 75 without them); the
 * module is opened only when --screenshot is given.
 */
#include "pcl_phaser_align_screenshot.h"
#include "tool_module.h"

namespace pcl {
namespace phaser {

namespace {

using CheckFunction = bool (*)(std::string&);
using SaveFunction = bool (*)(const pcl::PointCloud<pcl::PointXYZRGB>::ConstPtr&,
                              const std::string&, int, int, std::string&);

/** \brief The module, opened once (and kept loaded: VTK must not be unloaded while the
 * process runs). */
const ToolModule& screenshotModule()
{
#ifndef PCL_PHASER_SCREENSHOT_MODULE
  static const ToolModule module(
      "this pcl_phaser_align was built without pcl_visualization (PCL's "
      "visualization component was not found), so it cannot render screenshots");
#else
  static const ToolModule module(
      "the screenshot module", PCL_PHASER_SCREENSHOT_MODULE,
      {"pcl_phaser_can_save_screenshot", "pcl_phaser_save_overlay_screenshot"});
#endif
  return module;
}

} // namespace

bool canSaveScreenshot(std::string& reason)
{
  const ToolModule& module = screenshotModule();
  const auto check = module.entry<CheckFunction>(0);
  if (!check) {
    reason = module.reason();
    return (false);
  }
  return (check(reason));
}

bool saveOverlayScreenshot(const pcl::PointCloud<pcl::PointXYZRGB>::ConstPtr& cloud,
                           const std::string& path, int width, int height,
                           std::string& error)
{
  const ToolModule& module = screenshotModule();
  const auto save = module.entry<SaveFunction>(1);
  if (!save) {
    error = module.reason();
    return (false);
  }
  return (save(cloud, path, width, height, error));
}

} // namespace phaser
} // namespace pcl
