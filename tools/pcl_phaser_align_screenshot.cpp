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

#include <dlfcn.h>

namespace pcl {
namespace phaser {

namespace {

using CheckFunction = bool (*)(std::string&);
using SaveFunction = bool (*)(const pcl::PointCloud<pcl::PointXYZRGB>::ConstPtr&,
                              const std::string&, int, int, std::string&);

/** \brief The module's entry points, opened once (the module stays loaded: VTK must not
 * be unloaded while the process runs); both null, with \a reason, when it cannot be. */
struct ScreenshotModule {
  CheckFunction check = nullptr;
  SaveFunction save = nullptr;
  std::string reason;
};

const ScreenshotModule& screenshotModule()
{
  static const ScreenshotModule module = [] {
    ScreenshotModule m;
#ifndef PCL_PHASER_SCREENSHOT_MODULE
    m.reason =
        "this pcl_phaser_align was built without pcl_visualization (PCL's "
        "visualization component was not found), so it cannot render screenshots";
#else
    // Found like the tool's libraries: its RUNPATH, the build tree or ../lib.
    void* handle = dlopen(PCL_PHASER_SCREENSHOT_MODULE, RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = dlerror();
      m.reason = std::string("cannot load the screenshot module ") +
                 PCL_PHASER_SCREENSHOT_MODULE + ": " + (why ? why : "unknown error");
      return m;
    }
    m.check = reinterpret_cast<CheckFunction>(
        dlsym(handle, "pcl_phaser_can_save_screenshot"));
    m.save = reinterpret_cast<SaveFunction>(
        dlsym(handle, "pcl_phaser_save_overlay_screenshot"));
    if (!m.check || !m.save) {
      m.check = nullptr;
      m.save = nullptr;
      m.reason = std::string("the screenshot module ") + PCL_PHASER_SCREENSHOT_MODULE +
                 " lacks its entry points (a module of another version?)";
    }
#endif
    return m;
  }();
  return module;
}

} // namespace

bool canSaveScreenshot(std::string& reason)
{
  const ScreenshotModule& module = screenshotModule();
  if (!module.check) {
    reason = module.reason;
    return (false);
  }
  return (module.check(reason));
}

bool saveOverlayScreenshot(const pcl::PointCloud<pcl::PointXYZRGB>::ConstPtr& cloud,
                           const std::string& path, int width, int height,
                           std::string& error)
{
  const ScreenshotModule& module = screenshotModule();
  if (!module.save) {
    error = module.reason;
    return (false);
  }
  return (module.save(cloud, path, width, height, error));
}

} // namespace phaser
} // namespace pcl
