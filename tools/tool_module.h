// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file tool_module.h
 * \brief A module of a tool (a shared object opened with dlopen on first use and kept
 * loaded): its named entry points, or the reason it cannot serve.
 */
#pragma once

#include <algorithm>
#include <dlfcn.h>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace pcl {
namespace phaser {

/** \brief The entry points of one module, looked up once; none, with reason(), when
 *  the module cannot be loaded or lacks any of them. */
class ToolModule {
public:
  /** \brief Open \a file (found like the tool's libraries: its RUNPATH, the build tree
   *  or ../lib) and look up \a names.
   *  \param[in] what the module in messages, e.g. "the ICP module" */
  ToolModule(const std::string& what, const char* file,
             std::initializer_list<const char*> names)
  {
    void* handle = dlopen(file, RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = dlerror();
      reason_ =
          "cannot load " + what + " " + file + ": " + (why ? why : "unknown error");
      return;
    }
    for (const char* name : names)
      entries_.push_back(dlsym(handle, name));
    if (std::find(entries_.begin(), entries_.end(), nullptr) != entries_.end()) {
      entries_.clear();
      reason_ =
          what + " " + file + " lacks its entry points (a module of another version?)";
    }
  }

  /** \brief A module this build cannot have, for \a reason. */
  explicit ToolModule(std::string reason)
      : reason_(std::move(reason))
  {
  }

  /** \brief Entry point \a i (the position of its name) as a \a Function; null when the
   *  module cannot serve. */
  template <typename Function>
  Function entry(std::size_t i) const
  {
    return i < entries_.size() ? reinterpret_cast<Function>(entries_[i]) : nullptr;
  }

  /** \brief Why entry() is null. */
  const std::string& reason() const { return reason_; }

private:
  std::vector<void*> entries_;
  std::string reason_;
};

} // namespace phaser
} // namespace pcl
