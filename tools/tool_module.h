// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file tool_module.h
 * \brief A module of a tool, opened with dlopen on first use and kept loaded.
 */
#pragma once

#include <algorithm>
#include <dlfcn.h>
#include <initializer_list>
#include <string>
#include <vector>

namespace pcl {
namespace phaser {

/** \brief The entry points of a module, by the position of their names; none, with
 *  reason(), when it cannot be loaded (\a what names it: "the ICP module") or lacks
 *  one, or when built with a reason alone. */
class ToolModule {
public:
  ToolModule(const std::string& what, const char* file,
             std::initializer_list<const char*> names)
  {
    // Found like the tool's libraries: its RUNPATH, the build tree or ../lib.
    void* handle = dlopen(file, RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = dlerror();
      reason_ =
          "cannot load " + what + " " + file + ": " + (why ? why : "unknown error");
      return;
    }
    for (const char* name : names)
      entries_.push_back(dlsym(handle, name));
    if (std::count(entries_.begin(), entries_.end(), nullptr) > 0) {
      entries_.clear();
      reason_ =
          what + " " + file + " lacks its entry points (a module of another version?)";
    }
  }
  explicit ToolModule(std::string reason)
      : reason_(std::move(reason))
  {
  }

  /** \brief Entry point \a i as a \a Function; null when the module cannot serve. */
  template <typename Function>
  Function entry(std::size_t i) const
  {
    return i < entries_.size() ? reinterpret_cast<Function>(entries_[i]) : nullptr;
  }
  const std::string& reason() const { return reason_; }

private:
  std::vector<void*> entries_;
  std::string reason_;
};

} // namespace phaser
} // namespace pcl
