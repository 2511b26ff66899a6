/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * PCL's local aligners, started from identity (to show why a global initializer is
 * needed), and the ICP refinement that may follow any method.
 */
#include "methods.h"

#include <pcl/registration/gicp.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/ndt.h>

namespace pcl::phaser {
namespace bench {

namespace {

using XYZ = pcl::PointXYZ;

template <typename Aligner>
MethodResult runLocal(Aligner& aligner, const Cloud& source, const Cloud& target,
                      const MethodSettings& settings, const Eigen::Matrix4d& initial)
{
  const auto start = std::chrono::steady_clock::now();
  const auto s = downsampleXYZ(source, settings.voxel);
  const auto t = downsampleXYZ(target, settings.voxel);
  MethodResult result;
  result.transformation = initial;
  if (s->size() < 3 || t->size() < 3)
    return result;
  aligner.setInputSource(s);
  aligner.setInputTarget(t);
  pcl::PointCloud<XYZ> aligned;
  aligner.align(aligned, initial.cast<float>());
  result.ms = elapsedMs(start);
  result.transformation = aligner.getFinalTransformation().template cast<double>();
  result.converged = aligner.hasConverged();
  result.score = aligner.getFitnessScore(4.0 * settings.voxel * settings.voxel);
  return result;
}

/** ICP and GICP share their stopping rules. */
template <typename Aligner>
MethodResult runIcpLike(Aligner& aligner, const Cloud& source, const Cloud& target,
                        const MethodSettings& settings, const Eigen::Matrix4d& initial)
{
  aligner.setMaxCorrespondenceDistance(2.0 * settings.voxel);
  aligner.setMaximumIterations(50);
  aligner.setTransformationEpsilon(1e-10);
  return runLocal(aligner, source, target, settings, initial);
}

} // namespace

MethodResult runIcp(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                    const MethodSettings& settings)
{
  pcl::IterativeClosestPoint<XYZ, XYZ> icp;
  return runIcpLike(icp, *source, *target, settings, Eigen::Matrix4d::Identity());
}

MethodResult runGicp(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                     const MethodSettings& settings)
{
  pcl::GeneralizedIterativeClosestPoint<XYZ, XYZ> gicp;
  return runIcpLike(gicp, *source, *target, settings, Eigen::Matrix4d::Identity());
}

MethodResult runNdt(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                    const MethodSettings& settings)
{
  pcl::NormalDistributionsTransform<XYZ, XYZ> ndt;
  ndt.setResolution(static_cast<float>(4.0 * settings.voxel));
  ndt.setStepSize(0.1);
  ndt.setMaximumIterations(50);
  ndt.setTransformationEpsilon(1e-6);
  return runLocal(ndt, *source, *target, settings, Eigen::Matrix4d::Identity());
}

void refineWithIcp(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                   const MethodSettings& settings, MethodResult& result)
{
  pcl::IterativeClosestPoint<XYZ, XYZ> icp;
  const MethodResult refined =
      runIcpLike(icp, *source, *target, settings, result.transformation);
  result.transformation = refined.transformation;
  result.ms += refined.ms;
}

} // namespace bench
} // namespace pcl::phaser
