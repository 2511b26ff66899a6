// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file pcl_phaser_align_icp.cpp
 * \brief The loader of the ICP module (icp_module.cpp), opened on the first -icp.
 */
#include "pcl_phaser_align_icp.h"
#include "tool_module.h"

#include <type_traits>

namespace pcl {
namespace phaser {
namespace align_tool {

namespace {

template <typename PointT>
using RefineFunction = void (*)(const typename pcl::PointCloud<PointT>::Ptr&,
                                const typename pcl::PointCloud<PointT>::Ptr&,
                                const Eigen::Matrix4d&, const IcpSettings&, Stage&,
                                IcpRun&);

/** The module, opened on the first -icp (and kept loaded). */
const ToolModule& icpModule()
{
  static const ToolModule module(
      "the ICP module", PCL_PHASER_ICP_MODULE,
      {"pcl_phaser_icp_refine_xyz", "pcl_phaser_icp_refine_xyzi"});
  return module;
}

} // namespace

template <typename PointT>
bool refineInModule(const typename pcl::PointCloud<PointT>::Ptr& source,
                    const typename pcl::PointCloud<PointT>::Ptr& target,
                    const Eigen::Matrix4d& guess, const IcpSettings& settings, Stage& s,
                    IcpRun& run, std::string& error)
{
  const ToolModule& module = icpModule();
  const auto refine =
      module.entry<RefineFunction<PointT>>(std::is_same_v<PointT, pcl::PointXYZI>);
  if (!refine) {
    error = module.reason();
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
