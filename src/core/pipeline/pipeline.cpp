/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "pipeline/pipeline_internal.h"
#include "support/error.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace pcl::phaser {

namespace {

using detail::Clock;
using detail::msSince;

SpatialGridParameters gridParameters(const PhaserParameters& p)
{
  SpatialGridParameters g;
  g.grid_size = p.spatial_grid_size;
  g.voxel_size = p.voxel_size;
  return g;
}

/** Fused spherical spectrum of a cloud; throws when the cloud carries no spherical
 *  signal. */
SphericalSpectrum sphericalSpectrum(const Eigen::Matrix3Xd& points,
                                    const ChannelValues& channels,
                                    const PhaserParameters& p, const char* which,
                                    double& sampling_ms, double& sht_ms,
                                    SphericalSupport* support = nullptr)
{
  int observed = 0;
  SphericalSpectrum F =
      cloudSphericalSpectrum(points, channels, p.bandwidth, p.fusion_levels,
                             p.num_threads, observed, sampling_ms, sht_ms, support);
  if (observed < 2)
    throw InvalidArgument(
        std::string(which) +
        " cloud has fewer than two distinct directions from its "
        "projection center (empty, all at the center, or a single point)");
  if (!(spectrumSquaredNorm(F) > 0.0))
    throw InvalidArgument(std::string(which) + " cloud is constant on the sphere");
  return F;
}

/** The target points inside the cube that holds the inner 75% of them (by distance from
 *  the center): after the first pass the residual shift is small, so a fine grid over
 *  the densely observed region measures it best. */
std::vector<Eigen::Index> innerRegion(const Eigen::Matrix3Xd& points)
{
  std::vector<double> r(points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    r[i] = points.col(i).cwiseAbs().maxCoeff();
  std::vector<double> sorted = r;
  const std::size_t k = (sorted.size() * 3) / 4;
  std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
  const double half = sorted[k];
  std::vector<Eigen::Index> inner;
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    if (r[i] <= half)
      inner.push_back(i);
  return inner;
}

/** The verification samples of \a points: one (the centroid) per cube of \a radius,
 *  evenly every k-th of them when there are more than kMaxVerificationSamples (k =
 *  ceil(n / kMaxVerificationSamples)). */
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

} // namespace

namespace detail {

double msSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/** The source's spherical spectrum, timed; with its support when \a support is given.
 */
SphericalSpectrum sourceSpectrum(const Eigen::Matrix3Xd& points,
                                 const ChannelValues& channels,
                                 const PhaserParameters& p, PhaserResult& e,
                                 SphericalSupport* support)
{
  return sphericalSpectrum(points, channels, p, "source", e.sampling_ms, e.sht_ms,
                           support);
}

/** The global search: C on the SO(3) grid. */
So3CorrelationGrid correlateRotation(const TargetModel& target,
                                     const SphericalSpectrum& H,
                                     const PhaserParameters& p, PhaserResult& e)
{
  const auto t = Clock::now();
  So3CorrelationGrid C = So3Correlator::instance(p.bandwidth)
                             ->correlate(target.spherical, H, p.num_threads);
  e.so3_ms += msSince(t);
  return C;
}

/** Newton refinement of \a R on C, timed; with PhaserParameters::normalized_refinement
 *  then on the energy-normalized correlation (see refineRotation: plain C leans towards
 *  equal sensor tilt) near that maximum, with the supports given. Returns the exact C
 *  at the result through \a value. */
Eigen::Matrix3d refine(const TargetModel& target, const SphericalSpectrum& H,
                       const SphericalSupport& support, const Eigen::Matrix3d& R,
                       const PhaserParameters& p, double& value, PhaserResult& e)
{
  const auto t = Clock::now();
  RefinedRotation refined = refineRotation(target.spherical, H, R, p.bandwidth,
                                           p.refinement_iterations, p.num_threads);
  if (p.normalized_refinement)
    refined = refineRotation(target.spherical, H, refined.rotation, p.bandwidth,
                             p.refinement_iterations, p.num_threads,
                             &target.spherical_support, &support,
                             normalizedRefinementRadius(p.bandwidth));
  value = refined.value;
  e.refinement_ms += msSince(t);
  return refined.rotation;
}

/** Correlation peak over the norms of the two grids (0 when one is empty). */
double normalizedPeak(double peak, double energy_product)
{
  return energy_product > 0.0 ? peak / std::sqrt(energy_product) : 0.0;
}

/** Grid samples around a peak as rotations of the final estimate: each sample's offset
 *  from the peak, delta_i = R_i R_peak^T, applied on the left of \a estimate (so the
 *  spread is expressed in the target frame), with weights from the correlation above
 * the lowest value of the block. */
void rotationSamples(const So3CorrelationGrid& C, const So3GridIndex& peak,
                     const Eigen::Matrix3d& estimate, PhaserResult& e)
{
  const std::vector<RotationSample> block = rotationNeighborhood(C, peak, 1);
  const Eigen::Matrix3d R_peak =
      rotationFromEuler(gridEuler(peak, C.outputBandwidth()));
  double lowest = block.front().value;
  for (const RotationSample& s : block)
    lowest = std::min(lowest, s.value);
  e.rotation_samples.clear();
  e.rotation_weights.clear();
  for (const RotationSample& s : block) {
    const Eigen::Quaterniond q(s.rotation * R_peak.transpose() * estimate);
    e.rotation_samples.emplace_back(q.w(), q.x(), q.y(), q.z());
    e.rotation_weights.push_back(s.value - lowest);
  }
}

/** Binary occupancy spectrum of \a points on \a grid. */
SpatialSpectrum occupancySpectrum(const SpatialGrid& grid,
                                  const Eigen::Matrix3Xd& points, int num_threads)
{
  SpatialVoxelParameters voxel;
  voxel.saturation = kOccupancySaturation;
  voxel.num_threads = num_threads;
  return computeSpectrum(voxelize(grid, points, voxel), num_threads);
}

double volumeAt(const SpatialVolume& v, const Eigen::Vector3i& i)
{
  return v.values[v.grid.flatIndex(i.x(), i.y(), i.z())];
}

/** Translation of the (already rotated) \a points onto \a target by the occupancy
 *  correlation, whitened by \a whitening (correlateSpectraWhitened), sub-voxel peak.
 *  When \a volume is given (the final stage), the plain correlation volume is kept for
 *  the covariance and the peak's sidelobe score is computed. */
SpatialCorrelationResult shiftOf(const SpatialSpectrum& target,
                                 const Eigen::Matrix3Xd& points, double whitening,
                                 const PhaserParameters& p, PhaserResult& e,
                                 SpatialVolume* volume, double* source_energy)
{
  const auto t = Clock::now();
  SpatialSpectrum S = occupancySpectrum(target.grid, points, p.num_threads);
  if (source_energy)
    *source_energy = spectrumEnergy(S);
  SpatialVolume plain;
  if (volume && whitening > 0.0)
    plain = correlateSpectra(target, S, p.num_threads);
  SpatialVolume C =
      correlateSpectraWhitened(target, std::move(S), whitening, p.num_threads);
  const SpatialCorrelationResult shift = findSpatialPeak(
      C, SpatialPeakRefinement::kGaussian, p.num_threads, volume != nullptr);
  if (volume)
    *volume = whitening > 0.0 ? std::move(plain) : std::move(C);
  e.translation_ms += msSince(t);
  return shift;
}

namespace {

/** \a points indexed at \a radius with their patch normals, one point (the centroid)
 *  per cube of radius / kIndexThinning: distances move by a few centimeters, while a
 *  cell near the sensor held thousands of points. */
PointIndex thinnedIndex(const Eigen::Matrix3Xd& points, const SurfacePatches& patches,
                        double radius)
{
  const Eigen::Matrix3Xd thinned = voxelCentroids(points, radius / kIndexThinning);
  return PointIndex(thinned, radius, patchNormalsAt(patches, thinned));
}

/** The target's surface patches and what derives from them: the orientation histogram,
 *  the thickness, the verification index and, about sensor origins, the polish's reach
 *  index and the evenly spaced samples of the reverse free-space test with their
 *  weights (one thread). */
void addSurfaceModel(TargetModel& model, const Eigen::Matrix3Xd& points,
                     double coarse_voxel)
{
  const StageParameters& params = model.params;
  const SurfacePatches patches =
      surfacePatches(points, kPatchVoxels * coarse_voxel, Eigen::Vector3d::Zero());
  if (params.orientation_candidates > 0 && params.sensor_centered)
    model.orientation = orientationSpectrum(patches, params.orientation_bandwidth, 1);
  model.thickness = patches.thickness;
  const double radius = kVerificationVoxels * coarse_voxel;
  model.index = thinnedIndex(points, patches, radius);
  if (params.sensor_centered) {
    model.reach_index =
        thinnedIndex(points, patches, kPolishReachVoxels * coarse_voxel);
    model.samples = verificationSamples(points, radius);
    model.sample_weights = orientationWeights(patches, model.samples);
  }
}

/** The occupancy spectrum of the target's inner region, the fine grid of the later
 *  passes (one thread). */
void addFineGrid(TargetModel& model, const Eigen::Matrix3Xd& points)
{
  const std::vector<Eigen::Index> keep = innerRegion(points);
  Eigen::Matrix3Xd inner(3, keep.size());
  for (std::size_t i = 0; i < keep.size(); ++i)
    inner.col(i) = points.col(keep[i]);
  SpatialGridParameters fine_grid = gridParameters(model.params);
  fine_grid.padding = 0.1;
  fine_grid.min_margin = 2.0 * fine_grid.padding * inner.cwiseAbs().maxCoeff();
  model.fine = occupancySpectrum(makeSpatialGrid(inner, fine_grid), inner, 1);
  model.fine_energy = spectrumEnergy(model.fine);
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
  model->channels = channels.size();
  SpatialGridParameters coarse_grid;
  coarse_grid.grid_size = params.spatial_grid_size;
  coarse_grid.voxel_size = params.voxel_size;
  const SpatialGrid coarse = makeSpatialGrid(points, coarse_grid);
  StageParameters single = params;
  single.num_threads = 1;
  // Five independent parts as one-thread tasks, the longest first: each part gives the
  // same result on any thread count, and in turn they left the other threads idle.
  runTasks(5, params.num_threads, [&](int part) {
    switch (part) {
    case 0:
      addSurfaceModel(*model, points, coarse.voxel_size);
      break;
    case 1:
      if (params.passes > 1)
        addFineGrid(*model, points);
      break;
    case 2:
      model->coarse = occupancySpectrum(coarse, points, 1);
      model->coarse_energy = spectrumEnergy(model->coarse);
      break;
    case 3:
      if (params.sensor_centered)
        model->free_space = freeSpace(points, kFreeSpaceBandwidth,
                                      kFreeSpaceMargin * coarse.voxel_size, 1);
      break;
    default: {
      double sampling_ms = 0.0, sht_ms = 0.0; // not reported for the target
      model->spherical = sphericalSpectrum(
          points, channels, single, "target", sampling_ms, sht_ms,
          params.normalized_refinement ? &model->spherical_support : nullptr);
      model->spherical_norm = std::sqrt(spectrumSquaredNorm(model->spherical));
    }
    }
  });
  model->preparation_ms = msSince(start);
  return model;
}

namespace {

/** What the verification and the orientation hypotheses need of the source. */
SourceContext sourceContext(const TargetModel& target, const Eigen::Matrix3Xd& points,
                            const ChannelValues& channels, const StageParameters& p,
                            PhaserResult& e)
{
  const auto t = Clock::now();
  SourceContext s{target, points, channels, p, {}, {}, {}, {}};
  const double coarse_voxel = target.coarse.grid.voxel_size;
  // Four independent passes over the points as one-thread tasks, the longest first
  // (each gives the same result on any thread count; in turn they left the other
  // threads idle).
  runTasks(4, p.num_threads, [&](int part) {
    switch (part) {
    case 0:
      s.patches =
          surfacePatches(points, kPatchVoxels * coarse_voxel, Eigen::Vector3d::Zero());
      break;
    case 1:
      s.samples.points = verificationSamples(points, e.verification_radius);
      break;
    case 2:
      if (p.sensor_centered)
        s.free_space =
            freeSpace(points, kFreeSpaceBandwidth, kFreeSpaceMargin * coarse_voxel, 1);
      break;
    default:
      s.coarse_points = voxelCentroids(points, coarse_voxel / kIndexThinning);
    }
  });
  s.samples.weights = orientationWeights(s.patches, s.samples.points);
  s.samples.normals = patchNormalsAt(s.patches, s.samples.points);
  e.verification_ms += msSince(t);
  return s;
}

} // namespace

PhaserResult estimateCentered(const TargetModel& target, const Eigen::Matrix3Xd& points,
                              const StageParameters& p,
                              const ChannelValues& raw_channels)
{
  if (raw_channels.size() != target.channels)
    throw InvalidArgument("the source has " + std::to_string(raw_channels.size()) +
                          " channels, the target " + std::to_string(target.channels));
  const ChannelValues channels = normalizeChannels(raw_channels, points.cols());
  PhaserResult e;
  e.verification_radius = target.index.radius();
  const SourceContext s = sourceContext(target, points, channels, p, e);
  const SphericalSpectrum H = sourceSpectrum(points, channels, p, e);
  const So3CorrelationGrid C = correlateRotation(target, H, p, e);
  Pose pose = globalSearch(s, C, std::sqrt(spectrumSquaredNorm(H)), e);
  pose = reprojectionPasses(s, pose, e);
  finalStage(s, pose, e);
  return e;
}

} // namespace detail
} // namespace pcl::phaser
