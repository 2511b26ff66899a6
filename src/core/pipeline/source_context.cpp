/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The source's verification samples, patches, free space and thinned points.
 */
#include "pipeline/source_context.h"
#include "pipeline/stage_tasks.h"

namespace pcl::phaser::detail {
namespace {

/** Most samples a polish steps on (every k-th; the poses it reaches are verified on
 *  all): a Gauss-Newton step of six unknowns needs far fewer. */
constexpr Eigen::Index kMaxPolishSamples = 4096;
/** Points per verification sample from which clouds about centroids are verified: at
 *  one point per sample cube there are no neighbors within the radius. PCL's bun0 (397
 *  points) measures 1.0 and the office keypoints 1.07; the milk carton 1.9-3.8, the
 *  bunny views 2.4 and more, a Kinect frame 18. */
constexpr double kDenseSamples = 1.5;
/** Largest surface thickness, in verification radii, at which poses are verified. */
constexpr double kMaxThickness = 1.0 / 3.0;

/** Every k-th of \a all, at most kMaxPolishSamples of them (all when fewer). */
VerificationSamples polishSamples(const VerificationSamples& all)
{
  const Eigen::Index n = all.points.cols();
  if (n <= kMaxPolishSamples)
    return all;
  const Eigen::Index step = (n + kMaxPolishSamples - 1) / kMaxPolishSamples;
  const Eigen::Index m = (n + step - 1) / step;
  VerificationSamples kept;
  kept.points.resize(3, m);
  kept.weights.resize(m);
  if (all.normals.cols() != 0)
    kept.normals.resize(3, m);
  for (Eigen::Index i = 0; i < m; ++i) {
    kept.points.col(i) = all.points.col(i * step);
    kept.weights[i] = all.weights[i * step];
    if (all.normals.cols() != 0)
      kept.normals.col(i) = all.normals.col(i * step);
  }
  return kept;
}

} // namespace

bool SourceContext::canVerify() const
{
  const double limit = kMaxThickness * target.index.radius();
  return verification && patches.thickness <= limit && target.thickness <= limit;
}

VerificationClouds SourceContext::verificationClouds() const
{
  VerificationClouds clouds;
  clouds.target = &target.index;
  clouds.reach = &target.reach_index;
  clouds.samples = &samples;
  clouds.polish = &polish;
  if (settings.mode.viewpoints) {
    clouds.target_free_space = &target.free_space;
    clouds.source_free_space = &free_space;
  }
  clouds.target_samples = &target.samples;
  clouds.target_weights = &target.sample_weights;
  return clouds;
}

SourceContext sourceContext(const TargetModel& target, const Eigen::Matrix3Xd& points,
                            const ChannelValues& channels,
                            const StageSettings& settings, const AllowedPoses& allowed,
                            StageTimes& times)
{
  const auto start = Clock::now();
  SourceContext source{target, points, channels, settings, allowed, {}, {}, {}, {}, {}};
  const double coarse_voxel = target.coarse.grid.voxel_size;
  // Four independent passes over the points as one-thread tasks, the longest first.
  runTasks(4, settings.params.num_threads, [&](int part) {
    if (part == 0)
      source.patches =
          surfacePatches(points, kPatchVoxels * coarse_voxel, Eigen::Vector3d::Zero());
    else if (part == 1)
      source.samples.points = verificationSamples(points, target.index.radius());
    else if (part == 2 && settings.mode.source_viewpoint)
      source.free_space =
          freeSpace(points, kFreeSpaceBandwidth, kFreeSpaceMargin * coarse_voxel, 1);
    else if (part == 3)
      source.coarse_points = voxelCentroids(points, coarse_voxel / kIndexThinning);
  });
  source.samples.weights = orientationWeights(source.patches, source.samples.points);
  source.samples.normals = patchNormalsAt(source.patches, source.samples.points);
  source.polish = polishSamples(source.samples);
  times.verification += msSince(start);
  source.verification = settings.mode.sensor_centered ||
                        points.cols() >= kDenseSamples * source.samples.points.cols();
  return source;
}

} // namespace pcl::phaser::detail
