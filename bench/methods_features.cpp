/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * PCL's feature-based global aligners on FPFH, with the usual recipe: voxel v, normals
 * within 2 v, FPFH within 5 v (as in PCL's and Open3D's tutorials). Feature computation
 * is part of the measured time, and its stage "features" (both clouds); the aligner's
 * align() is the stage "search".
 */
#include "methods.h"

#include <pcl/features/fpfh_omp.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/registration/ia_ransac.h>
#include <pcl/registration/sample_consensus_prerejective.h>

#include <cstdlib>

namespace pcl::phaser {
namespace bench {

namespace {

using XYZ = pcl::PointXYZ;
using Features = pcl::PointCloud<pcl::FPFHSignature33>;

struct Described {
  pcl::PointCloud<XYZ>::Ptr points;
  Features::Ptr features;
};

Described describe(const Cloud& cloud, const MethodSettings& settings)
{
  Described d;
  d.points = downsampleXYZ(cloud, settings.voxel);
  auto normals = pcl::make_shared<pcl::PointCloud<pcl::Normal>>();
  pcl::NormalEstimationOMP<XYZ, pcl::Normal> ne(settings.threads);
  ne.setInputCloud(d.points);
  ne.setRadiusSearch(2.0 * settings.voxel);
  ne.compute(*normals);
  // FPFH needs finite normals: drop the points whose neighborhood was degenerate.
  auto points = pcl::make_shared<pcl::PointCloud<XYZ>>();
  auto kept_normals = pcl::make_shared<pcl::PointCloud<pcl::Normal>>();
  for (std::size_t i = 0; i < normals->size(); ++i)
    if (std::isfinite((*normals)[i].normal_x)) {
      points->push_back((*d.points)[i]);
      kept_normals->push_back((*normals)[i]);
    }
  d.points = points;
  d.features = pcl::make_shared<Features>();
  pcl::FPFHEstimationOMP<XYZ, pcl::Normal, pcl::FPFHSignature33> fpfh(settings.threads);
  fpfh.setInputCloud(d.points);
  fpfh.setInputNormals(kept_normals);
  fpfh.setRadiusSearch(5.0 * settings.voxel);
  fpfh.compute(*d.features);
  return d;
}

/** \brief \a aligner's align() after the features that took \a features_ms since
 *  \a start: the result, its time since \a start and its two stages. */
template <typename Aligner>
MethodResult finish(Aligner& aligner, const Described& source, double voxel,
                    std::chrono::steady_clock::time_point start, double features_ms)
{
  MethodResult result;
  if (source.points->size() < 3) // too few points for a 3-point sample: not attempted
    return result;
  pcl::PointCloud<XYZ> aligned;
  const auto search = std::chrono::steady_clock::now();
  aligner.align(aligned);
  result.stages = {{"features", features_ms}, {"search", elapsedMs(search)}};
  result.ms = elapsedMs(start);
  result.transformation = aligner.getFinalTransformation().template cast<double>();
  result.converged = aligner.hasConverged();
  result.score = aligner.getFitnessScore(4.0 * voxel * voxel); // pairs within 2 voxels
  return result;
}

} // namespace

MethodResult runSacIa(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                      const MethodSettings& settings)
{
  std::srand(settings.seed);
  const auto start = std::chrono::steady_clock::now();
  const Described s = describe(*source, settings), t = describe(*target, settings);
  const double features_ms = elapsedMs(start);
  pcl::SampleConsensusInitialAlignment<XYZ, XYZ, pcl::FPFHSignature33> sacia;
  sacia.setInputSource(s.points);
  sacia.setSourceFeatures(s.features);
  sacia.setInputTarget(t.points);
  sacia.setTargetFeatures(t.features);
  sacia.setMinSampleDistance(static_cast<float>(2.0 * settings.voxel));
  sacia.setMaxCorrespondenceDistance(2.0 * settings.voxel);
  sacia.setMaximumIterations(1000);
  sacia.setNumberOfSamples(3);
  sacia.setCorrespondenceRandomness(5);
  return finish(sacia, s, settings.voxel, start, features_ms);
}

MethodResult runPrerejective(const Cloud::ConstPtr& source,
                             const Cloud::ConstPtr& target,
                             const MethodSettings& settings)
{
  std::srand(settings.seed);
  const auto start = std::chrono::steady_clock::now();
  const Described s = describe(*source, settings), t = describe(*target, settings);
  const double features_ms = elapsedMs(start);
  pcl::SampleConsensusPrerejective<XYZ, XYZ, pcl::FPFHSignature33> prerejective;
  prerejective.setInputSource(s.points);
  prerejective.setSourceFeatures(s.features);
  prerejective.setInputTarget(t.points);
  prerejective.setTargetFeatures(t.features);
  prerejective.setMaximumIterations(10000); // PCL's tutorial: 50000, 10x slower here
  prerejective.setNumberOfSamples(3);
  prerejective.setCorrespondenceRandomness(5);
  prerejective.setSimilarityThreshold(0.9f);
  prerejective.setMaxCorrespondenceDistance(2.5 * settings.voxel);
  prerejective.setInlierFraction(0.25f);
  return finish(prerejective, s, settings.voxel, start, features_ms);
}

} // namespace bench
} // namespace pcl::phaser
