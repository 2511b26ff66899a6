// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file icp_refinement.h
 * \brief The ICP refinement of `pcl_phaser_align -icp` (settings:
 * pcl_phaser_align_icp.h): PCL's voxel grid, normal estimation and ICP. Compiled into
 * the ICP module (icp_module.cpp) and the tests, not into the tool.
 */
#pragma once

#include "pcl_phaser_align_icp.h"

#include <pcl/console/time.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/filters/filter.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/registration/icp.h>

#include <functional>
#include <type_traits>

namespace pcl {
namespace phaser {
namespace align_tool {

/** \brief \a cloud reduced to one centroid per occupied voxel of edge \a voxel_size,
 *  or \a cloud itself when \a voxel_size is 0. */
template <typename PointT>
typename pcl::PointCloud<PointT>::Ptr
downsample(const typename pcl::PointCloud<PointT>::Ptr& cloud, double voxel_size)
{
  if (!(voxel_size > 0.0))
    return cloud;
  auto out = pcl::make_shared<pcl::PointCloud<PointT>>();
  pcl::VoxelGrid<PointT> grid;
  const float leaf = static_cast<float>(voxel_size);
  grid.setLeafSize(leaf, leaf, leaf);
  grid.setInputCloud(cloud);
  grid.filter(*out);
  return out;
}

/** \brief A copy of \a cloud with normals from pcl::NormalEstimationOMP over
 *  \a neighbors neighbors; points whose normal is undefined are left out. */
template <typename NormalT, typename PointT>
typename pcl::PointCloud<NormalT>::Ptr withNormals(const pcl::PointCloud<PointT>& cloud,
                                                   int neighbors, unsigned threads)
{
  auto out = pcl::make_shared<pcl::PointCloud<NormalT>>();
  pcl::copyPointCloud(cloud, *out);
  pcl::NormalEstimationOMP<NormalT, NormalT> ne(threads);
  ne.setKSearch(neighbors);
  ne.setInputCloud(out);
  ne.compute(*out);
  pcl::Indices kept;
  pcl::removeNaNNormalsFromPointCloud(*out, *out, kept);
  return (out);
}

/** \brief A copy of \a cloud with zero normals: the source of point-to-plane ICP,
 *  whose error (pcl::registration::TransformationEstimationPointToPlaneLLS) uses the
 *  target's normals only. */
template <typename NormalT, typename PointT>
typename pcl::PointCloud<NormalT>::Ptr
withZeroNormals(const pcl::PointCloud<PointT>& cloud)
{
  auto out = pcl::make_shared<pcl::PointCloud<NormalT>>();
  pcl::copyPointCloud(cloud, *out);
  for (NormalT& p : *out)
    p.normal_x = p.normal_y = p.normal_z = p.curvature = 0.0f;
  return (out);
}

/** \brief Run \a icp (its clouds set) from \a guess with \a settings' criteria into
 *  \a s.transform, \a s.converged and \a run.iterations. */
template <typename Icp>
void runIcp(Icp& icp, const Eigen::Matrix4d& guess, const IcpSettings& settings,
            Stage& s, IcpRun& run)
{
  icp.setMaxCorrespondenceDistance(settings.max_distance);
  icp.setMaximumIterations(settings.iterations);
  icp.setTransformationEpsilon(settings.transformation_epsilon);
  if (settings.rotation_epsilon > 0.0)
    icp.setTransformationRotationEpsilon(1.0 - settings.rotation_epsilon);
  using Cloud = typename Icp::PointCloudSource;
  run.iterations = 0;
  std::function<void(const Cloud&, const pcl::Indices&,
                     const typename Icp::PointCloudTarget&, const pcl::Indices&)>
      count = [&run](const Cloud&, const pcl::Indices&,
                     const typename Icp::PointCloudTarget&,
                     const pcl::Indices&) { ++run.iterations; };
  icp.registerVisualizationCallback(count);
  Cloud aligned;
  icp.align(aligned, guess);
  s.converged = icp.hasConverged();
  s.transform = icp.getFinalTransformation();
}

/** \brief ICP from \a guess, in double precision (which also keeps GCC 12's false
 * -Warray-bounds in PCL's float SVD estimation away), on the source reduced by
 * downsample() to settings.source_voxel_size and the target to settings.voxel_size.
 * Point-to-plane by default: pcl::IterativeClosestPointWithNormals from the source
 * points to the target's withNormals() planes; with point_to_point, plain
 * pcl::IterativeClosestPoint.
 * \param[in] full_source,full_target finite clouds
 * \param[in] guess the initial T_target_source
 * \param[in] settings ICP parameters
 * \param[out] s transform, converged, time_ms and ran
 * \param[out] run the points and iterations used */
template <typename PointT>
void refine(const typename pcl::PointCloud<PointT>::Ptr& full_source,
            const typename pcl::PointCloud<PointT>::Ptr& full_target,
            const Eigen::Matrix4d& guess, const IcpSettings& settings, Stage& s,
            IcpRun& run)
{
  pcl::console::TicToc tt;
  tt.tic();
  const auto source = downsample<PointT>(full_source, settings.source_voxel_size);
  const auto target = downsample<PointT>(full_target, settings.voxel_size);
  const auto on = [&](auto& icp, const auto& src, const auto& tgt) {
    icp.setInputSource(src);
    icp.setInputTarget(tgt);
    run.source_points = src->size();
    run.target_points = tgt->size();
    runIcp(icp, guess, settings, s, run);
  };
  if (settings.point_to_point) {
    pcl::IterativeClosestPoint<PointT, PointT, double> icp;
    on(icp, source, target);
  } else {
    using NormalT = std::conditional_t<pcl::traits::has_intensity_v<PointT>,
                                       pcl::PointXYZINormal, pcl::PointNormal>;
    pcl::IterativeClosestPointWithNormals<NormalT, NormalT, double> icp;
    on(icp, withZeroNormals<NormalT>(*source),
       withNormals<NormalT>(*target, settings.normal_neighbors, settings.threads));
  }
  s.time_ms = tt.toc();
  s.ran = true;
}

} // namespace align_tool
} // namespace phaser
} // namespace pcl
