// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file pcl_phaser_align_icp.cpp
 * \brief The loader of the ICP module (icp_module.cpp), opened on the first -icp.
 */
#include "pcl_phaser_align_icp.h"

#include <dlfcn.h>

namespace pcl {
namespace phaser {
namespace align_tool {

namespace {

template <typename PointT>
using RefineFunction = void (*)(const typename pcl::PointCloud<PointT>::Ptr&,
                                const typename pcl::PointCloud<PointT>::Ptr&,
                                const Eigen::Matrix4d&, const IcpSettings&, Stage&,
                                IcpRun&);

/** The module's entry points, opened once (and kept loaded); null, with \a reason,
 *  when it cannot be. */
struct IcpModule {
  RefineFunction<pcl::PointXYZ> xyz = nullptr;
  RefineFunction<pcl::PointXYZI> xyzi = nullptr;
  std::string reason;
};

const IcpModule& icpModule()
{
  static const IcpModule module = [] {
    IcpModule m;
    // Found like the tool's libraries: its RUNPATH, the build tree or ../lib.
    void* handle = dlopen(PCL_PHASER_ICP_MODULE, RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = dlerror();
      m.reason = std::string("cannot load the ICP module ") + PCL_PHASER_ICP_MODULE +
                 ": " + (why ? why : "unknown error");
      return m;
    }
    m.xyz = reinterpret_cast<RefineFunction<pcl::PointXYZ>>(
        dlsym(handle, "pcl_phaser_icp_refine_xyz"));
    m.xyzi = reinterpret_cast<RefineFunction<pcl::PointXYZI>>(
        dlsym(handle, "pcl_phaser_icp_refine_xyzi"));
    if (!m.xyz || !m.xyzi) {
      m.xyz = nullptr;
      m.xyzi = nullptr;
      m.reason = std::string("the ICP module ") + PCL_PHASER_ICP_MODULE +
                 " lacks its entry points (a module of another version?)";
    }
    return m;
  }();
  return module;
}

template <typename PointT>
RefineFunction<PointT> entry(const IcpModule& module)
{
  if constexpr (std::is_same_v<PointT, pcl::PointXYZI>)
    return module.xyzi;
  else
    return module.xyz;
}

} // namespace

template <typename PointT>
bool refineInModule(const typename pcl::PointCloud<PointT>::Ptr& source,
                    const typename pcl::PointCloud<PointT>::Ptr& target,
                    const Eigen::Matrix4d& guess, const IcpSettings& settings, Stage& s,
                    IcpRun& run, std::string& error)
{
  const IcpModule& module = icpModule();
  const RefineFunction<PointT> refine = entry<PointT>(module);
  if (!refine) {
    error = module.reason;
    return (false);
  }
  refine(source, target, guess, settings, s, run);
  return (true);
}

template bool refineInModule<pcl::PointXYZ>(const pcl::PointCloud<pcl::PointXYZ>::Ptr&,
                                            const pcl::PointCloud<pcl::PointXYZ>::Ptr&,
                                            const Eigen::Matrix4d&, const IcpSettings&,
                                            Stage&, IcpRun&, std::string&);
template bool
refineInModule<pcl::PointXYZI>(const pcl::PointCloud<pcl::PointXYZI>::Ptr&,
                               const pcl::PointCloud<pcl::PointXYZI>::Ptr&,
                               const Eigen::Matrix4d&, const IcpSettings&, Stage&,
                               IcpRun&, std::string&);

} // namespace align_tool
} // namespace phaser
} // namespace pcl
