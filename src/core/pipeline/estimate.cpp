/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The target model, the source context and the order of the stages of one estimate.
 */
#include "pipeline/estimate.h"
#include "pipeline/global_search.h"
#include "pipeline/pipeline_stages.h"
#include "pipeline/pipeline_verdict.h"
#include "priors/tilt_prior.h"

namespace pcl::phaser {
namespace detail {
namespace {

/** Verification radius, in coarse voxels. */
constexpr double kVerificationVoxels = 0.5;
/** Radius of the index the local refinement's first step uses: a coarse peak a voxel
 *  off has too few samples (the ground) within kVerificationVoxels. */
constexpr double kReachVoxels = 1.0;
/** The indexes and pass-1 occupancy keep one point per cube of radius / this. */
constexpr double kIndexThinning = 8.0;
/** Most verification samples of either cloud: an inlier share from this many has a
 *  standard error below 0.004 (a LiDAR scan gives about 3,000). */
constexpr Eigen::Index kMaxVerificationSamples = 16384;
/** Most samples a polish steps on (every k-th; the poses it reaches are verified on
 *  all): a Gauss-Newton step of six unknowns needs far fewer. */
constexpr Eigen::Index kMaxPolishSamples = 4096;
/** Points per verification sample from which clouds about centroids are verified: at
 *  one point per sample cube there are no neighbors within the radius. PCL's bun0 (397
 *  points) measures 1.0 and the office keypoints 1.07; the milk carton 1.9-3.8, the
 *  bunny views 2.4 and more, a Kinect frame 18. */
constexpr double kDenseSamples = 1.5;
/** Direction cells of the free-space test (1.4 deg) and its margin in coarse voxels. */
constexpr int kFreeSpaceBandwidth = 128;
constexpr double kFreeSpaceMargin = 1.0;
/** Patches of the orientation histogram, in coarse voxels. */
constexpr double kPatchVoxels = 1.0;

/** The points in the cube holding the inner 75%: densely observed, for the fine grid.
 */
Eigen::Matrix3Xd innerRegion(const Eigen::Matrix3Xd& points)
{
  std::vector<double> r(points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    r[i] = points.col(i).cwiseAbs().maxCoeff();
  std::vector<double> sorted = r;
  const std::size_t k = (sorted.size() * 3) / 4;
  std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    if (r[i] <= sorted[k])
      keep.push_back(i);
  Eigen::Matrix3Xd inner(3, keep.size());
  for (std::size_t i = 0; i < keep.size(); ++i)
    inner.col(i) = points.col(keep[i]);
  return inner;
}

/** One sample per cube of \a radius; every k-th beyond kMaxVerificationSamples. */
Eigen::Matrix3Xd verificationSamples(const Eigen::Matrix3Xd& points, double radius)
{
  Eigen::Matrix3Xd all = voxelCentroids(points, radius);
  if (all.cols() <= kMaxVerificationSamples)
    return all;
  const Eigen::Index step =
      (all.cols() + kMaxVerificationSamples - 1) / kMaxVerificationSamples;
  Eigen::Matrix3Xd kept(3, (all.cols() + step - 1) / step);
  for (Eigen::Index i = 0; i < kept.cols(); ++i)
    kept.col(i) = all.col(i * step);
  return kept;
}

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

/** \a points thinned (kIndexThinning) and indexed at \a radius with patch normals. */
PointIndex thinnedIndex(const Eigen::Matrix3Xd& points, const SurfacePatches& patches,
                        double radius)
{
  const Eigen::Matrix3Xd thinned = voxelCentroids(points, radius / kIndexThinning);
  return PointIndex(thinned, radius, patchNormalsAt(patches, thinned));
}

/** The target's surface patches and what derives from them (one thread). */
void addSurfaceModel(TargetModel& model, const Eigen::Matrix3Xd& points,
                     double coarse_voxel)
{
  const StageParameters& params = model.params;
  const SurfacePatches patches =
      surfacePatches(points, kPatchVoxels * coarse_voxel, Eigen::Vector3d::Zero());
  if (params.orientation_candidates > 0)
    model.orientation = orientationSpectrum(patches, params.orientation_bandwidth, 1);
  model.thickness = patches.thickness;
  const double radius = kVerificationVoxels * coarse_voxel;
  model.index = thinnedIndex(points, patches, radius);
  model.reach_index = thinnedIndex(points, patches, kReachVoxels * coarse_voxel);
  model.samples = verificationSamples(points, radius);
  model.sample_weights = orientationWeights(patches, model.samples);
}

/** The fine grid of the later passes: the inner region, little padding (one thread). */
void addFineGrid(TargetModel& model, const Eigen::Matrix3Xd& points,
                 SpatialGridParameters grid)
{
  const Eigen::Matrix3Xd inner = innerRegion(points);
  grid.padding = 0.1;
  grid.min_margin = 2.0 * grid.padding * inner.cwiseAbs().maxCoeff();
  model.fine = occupancySpectrum(makeSpatialGrid(inner, grid), inner, 1);
  model.fine_energy = spectrumEnergy(model.fine);
}

/** What the verification and the orientation hypotheses need of the source. */
SourceContext sourceContext(const TargetModel& target, const Eigen::Matrix3Xd& points,
                            const ChannelValues& channels,
                            const StageParameters& params, StageTimes& times)
{
  const auto start = Clock::now();
  SourceContext source{target, points, channels, params, {}, {}, {}, {}, {}};
  const double coarse_voxel = target.coarse.grid.voxel_size;
  // Four independent passes over the points as one-thread tasks, the longest first.
  runTasks(4, params.num_threads, [&](int part) {
    if (part == 0)
      source.patches =
          surfacePatches(points, kPatchVoxels * coarse_voxel, Eigen::Vector3d::Zero());
    else if (part == 1)
      source.samples.points = verificationSamples(points, target.index.radius());
    else if (part == 2 && params.source_viewpoint)
      source.free_space =
          freeSpace(points, kFreeSpaceBandwidth, kFreeSpaceMargin * coarse_voxel, 1);
    else if (part == 3)
      source.coarse_points = voxelCentroids(points, coarse_voxel / kIndexThinning);
  });
  source.samples.weights = orientationWeights(source.patches, source.samples.points);
  source.samples.normals = patchNormalsAt(source.patches, source.samples.points);
  source.polish = polishSamples(source.samples);
  times.verification += msSince(start);
  return source;
}

} // namespace

std::shared_ptr<const TargetModel> prepareTarget(const Eigen::Matrix3Xd& points,
                                                 const StageParameters& params,
                                                 const ChannelValues& raw_channels)
{
  const auto start = Clock::now();
  const ChannelValues channels = normalizeChannels(raw_channels, points.cols());
  auto model = std::make_shared<TargetModel>();
  model->params = params;
  SpatialGridParameters grid;
  grid.grid_size = params.spatial_grid_size;
  grid.voxel_size = params.voxel_size;
  const SpatialGrid coarse = makeSpatialGrid(points, grid);
  StageParameters single = params;
  single.num_threads = 1;
  // Five one-thread tasks, the longest first: the same result on any thread count.
  runTasks(5, params.num_threads, [&](int part) {
    if (part == 0) {
      addSurfaceModel(*model, points, coarse.voxel_size);
    } else if (part == 1 && params.passes > 1) {
      addFineGrid(*model, points, grid);
    } else if (part == 2) {
      model->coarse = occupancySpectrum(coarse, points, 1);
      model->coarse_energy = spectrumEnergy(model->coarse);
    } else if (part == 3 && params.viewpoints) {
      model->free_space = freeSpace(points, kFreeSpaceBandwidth,
                                    kFreeSpaceMargin * coarse.voxel_size, 1);
    } else if (part == 4) {
      StageTimes unreported;
      model->spherical = sphericalSpectrum(
          points, channels, single, "target", unreported,
          params.normalized_refinement ? &model->spherical_support : nullptr);
      model->spherical_norm = std::sqrt(spectrumSquaredNorm(model->spherical));
    }
  });
  if (!params.viewpoints)
    model->magnitude = magnitudeShells(model->coarse, kMagnitudeBandwidth);
  model->preparation_ms = msSince(start);
  return model;
}

RigidPose estimateCentered(const TargetModel& target, const Eigen::Matrix3Xd& points,
                           const StageParameters& requested,
                           const ChannelValues& raw_channels, PhaserResult& result)
{
  StageParameters params = requested;
  params.orientation_candidates = tiltPriorOrientationCandidates(requested);
  const ChannelValues channels = normalizeChannels(raw_channels, points.cols());
  PhaserDiagnostics& diagnostics = result.diagnostics;
  StageTimes& times = diagnostics.times;
  diagnostics.verification_radius = target.index.radius();
  const SourceContext source = sourceContext(target, points, channels, params, times);
  params.verification = params.sensor_centered ||
                        points.cols() >= kDenseSamples * source.samples.points.cols();
  const SphericalSpectrum H =
      sphericalSpectrum(points, channels, params, "source", times);
  const auto start = Clock::now();
  const So3CorrelationGrid C = So3Correlator::instance(params.bandwidth)
                                   ->correlate(target.spherical, H, params.num_threads,
                                               tiltPriorRows(params, params.bandwidth));
  times.so3 += msSince(start);
  GlobalSearch search =
      globalSearch(source, C, std::sqrt(spectrumSquaredNorm(H)), times);
  result.chosen_hypothesis = search.chosen;
  diagnostics.hypotheses = std::move(search.hypotheses);
  diagnostics.passes = 1;
  Pose pose = search.decided
                  ? search.pose
                  : reprojectionPasses(source, search.pose, diagnostics.passes, times);
  pose = refineFinalPose(source, pose, search.decided, result);
  judgeFinalPose(source, pose, result);
  return pose;
}

} // namespace detail
} // namespace pcl::phaser
