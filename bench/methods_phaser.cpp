/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "methods.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/io.h>

namespace pcl::phaser {
namespace bench {

namespace {

/** \brief \a r without its lists, which no CSV column holds. */
PhaserResult withoutLists(PhaserResult r)
{
  r.diagnostics.hypotheses = {};
  r.diagnostics.rotation_samples = {};
  r.diagnostics.rotation_weights = {};
  return r;
}

template <typename PointP>
MethodResult align(const typename pcl::PointCloud<PointP>::ConstPtr& source,
                   const typename pcl::PointCloud<PointP>::ConstPtr& target,
                   const MethodSettings& settings, double setup_ms)
{
  const auto start = std::chrono::steady_clock::now();
  pcl::PhaserRegistration<PointP, PointP> phaser;
  pcl::phaser::PhaserParameters params = settings.engine;
  params.bandwidth = settings.bandwidth;
  params.num_threads = settings.threads;
  params.normalized_refinement =
      settings.normalized_refinement && settings.engine.normalized_refinement;
  if (settings.centroid)
    params.projection_center = pcl::phaser::ProjectionCenter::Centroid;
  phaser.setParameters(params);
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  pcl::PointCloud<PointP> aligned;
  phaser.align(aligned);
  MethodResult result;
  result.ms = setup_ms + elapsedMs(start);
  result.transformation = phaser.getFinalTransformation().template cast<double>();
  result.converged = phaser.hasConverged();
  result.phaser = withoutLists(phaser.getResult());
  result.score = result.phaser->diagnostics.translation_score;
  visitStageTimes(result.phaser->diagnostics.times, [&](const char* name, double ms) {
    result.stages.emplace_back(name, ms);
  });
  if (result.converged) {
    result.covariance = phaser.getCovariance();
    result.has_covariance = true;
  }
  return result;
}

} // namespace

MethodResult runPhaser(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                       const MethodSettings& settings, bool fuse_intensity)
{
  if (fuse_intensity)
    return align<PointT>(source, target, settings, 0.0);
  // Range only: the clouds as PointXYZ, as a user without intensity would have them.
  auto s = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  auto t = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::copyPointCloud(*source, *s);
  pcl::copyPointCloud(*target, *t);
  return align<pcl::PointXYZ>(s, t, settings, 0.0); // the copy is not the method's time
}

} // namespace bench
} // namespace pcl::phaser
