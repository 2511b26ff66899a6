/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * PCL's 4-points congruent sets aligners (FPCS, and KFPCS, its keypoint variant) on the
 * voxel-downsampled clouds, with a time limit (they have no other bound on their run).
 */
#include "methods.h"

#include <pcl/registration/ia_fpcs.h>
#include <pcl/registration/ia_kfpcs.h>

#include <cstdlib>

namespace pcl::phaser {
namespace bench {

MethodResult runFpcs(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                     const MethodSettings& settings, bool keypoint_variant)
{
  using XYZ = pcl::PointXYZ;
  std::srand(settings.seed);
  const auto start = std::chrono::steady_clock::now();
  const auto s = downsampleXYZ(*source, settings.voxel);
  const auto t = downsampleXYZ(*target, settings.voxel);
  MethodResult result;
  if (s->size() < 4 || t->size() < 4)
    return result;
  pcl::PointCloud<XYZ> aligned;
  auto configure = [&](auto& aligner) {
    aligner.setInputSource(s);
    aligner.setInputTarget(t);
    aligner.setNumberOfThreads(settings.threads);
    aligner.setApproxOverlap(0.7f);
    aligner.setDelta(static_cast<float>(settings.voxel), false);
    aligner.setMaxComputationTime(settings.fpcs_seconds);
    aligner.align(aligned);
    result.transformation = aligner.getFinalTransformation().template cast<double>();
    result.converged = aligner.hasConverged();
  };
  if (keypoint_variant) {
    pcl::registration::KFPCSInitialAlignment<XYZ, XYZ> kfpcs;
    kfpcs.setScoreThreshold(0.001f);
    configure(kfpcs);
  } else {
    pcl::registration::FPCSInitialAlignment<XYZ, XYZ> fpcs;
    fpcs.setNumberOfSamples(200);
    configure(fpcs);
  }
  result.ms = elapsedMs(start);
  return result;
}

} // namespace bench
} // namespace pcl::phaser
