/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Later passes, final refinement and the steps they share with the global search.
 */
#include "pipeline/pipeline_stages.h"
#include "pipeline/pipeline_verdict.h"
#include "priors/region.h"

namespace pcl::phaser {
namespace detail {

/** The source seen from a pose: spectrum, support, residual grid and its peak. */
struct Viewpoint {
  SphericalSpectrum H;
  SphericalSupport support;
  std::shared_ptr<const So3CorrelationGrid> grid;
  So3GridIndex peak{};
};

namespace {

/** Binary occupancy: the near-sensor density must not vote for stacking the sensors. */
constexpr double kOccupancySaturation = 0.05;

/** How far (at B = 64, scaled by 64 / B) the normalized refinement may move from the
 *  maximum of plain C; chosen on the demo pairs and the NEES study. */
constexpr double kNormalizedRefinementRadius = 0.75 * M_PI / 180.0;
/** Largest tilt of the residual rotation: a pass-1 residual is a few cells. */
constexpr double kResidualTilt = 20.0 * M_PI / 180.0;
/** Gauss-Newton steps of the local refinement on the verification samples. */
constexpr int kLocalRefinementSteps = 10;

/** Whether \a next replaces \a current (by rank when verifiable). */
bool improves(const Pose& next, const Pose& current)
{
  return !current.verifiable || next.verification.rank > current.verification.rank;
}

/** The residual grid from \a H and its peak (for a verifiable pose, within a cell or
 *  two: the one near the identity) into \a pose. */
void residualGrid(const SourceContext& source, const SphericalSpectrum& H, Pose& pose,
                  StageTimes& times)
{
  const auto start = Clock::now();
  const StageParameters& params = source.params;
  const int rows = betaRowsForTilt(params.bandwidth, kResidualTilt);
  auto C = std::make_shared<So3CorrelationGrid>(
      So3Correlator::instance(params.bandwidth)
          ->correlate(source.target.spherical, H, params.num_threads, rows));
  times.so3 += msSince(start);
  pose.peak = pose.verifiable ? C->argmaxNearIdentity(kHypothesisSeparation)
                              : C->argmax(params.num_threads);
  pose.grid = std::move(C);
}

/** Newton refinement of \a R on C, then on the energy-normalized correlation (plain C
 *  leans towards equal sensor tilt); the exact C at the result into \a value. */
Eigen::Matrix3d refineResidualRotation(const SourceContext& source,
                                       const Viewpoint& view, const Eigen::Matrix3d& R,
                                       double& value, StageTimes& times)
{
  const auto start = Clock::now();
  const StageParameters& params = source.params;
  const TargetModel& target = source.target;
  RefinedRotation refined =
      refineRotation(target.spherical, view.H, R, params.bandwidth,
                     params.refinement_iterations, params.num_threads);
  if (params.normalized_refinement)
    refined = refineRotation(
        target.spherical, view.H, refined.rotation, params.bandwidth,
        params.refinement_iterations, params.num_threads, &target.spherical_support,
        &view.support, kNormalizedRefinementRadius * 64.0 / params.bandwidth);
  value = refined.value;
  times.refinement += msSince(start);
  return refined.rotation;
}

/** Grid samples around \a peak moved with \a estimate, weighted above the lowest. */
void rotationSamples(const So3CorrelationGrid& C, const So3GridIndex& peak,
                     const Eigen::Matrix3d& estimate, PhaserDiagnostics& diagnostics)
{
  const std::vector<RotationSample> block = rotationNeighborhood(C, peak, 1);
  const Eigen::Matrix3d R_peak =
      rotationFromEuler(gridEuler(peak, C.outputBandwidth()));
  double lowest = block.front().value;
  for (const RotationSample& sample : block)
    lowest = std::min(lowest, sample.value);
  diagnostics.rotation_samples.clear();
  diagnostics.rotation_weights.clear();
  for (const RotationSample& sample : block) {
    const Eigen::Quaterniond q(sample.rotation * R_peak.transpose() * estimate);
    diagnostics.rotation_samples.emplace_back(q.w(), q.x(), q.y(), q.z());
    diagnostics.rotation_weights.push_back(sample.value - lowest);
  }
}

/** The source seen from \a pose. */
std::shared_ptr<Viewpoint> viewFrom(const SourceContext& source, const RigidPose& pose,
                                    StageTimes& times)
{
  auto view = std::make_shared<Viewpoint>();
  view->H = sphericalSpectrum(
      (pose.R * source.points).colwise() + pose.t, source.channels, source.params,
      "source", times, source.params.normalized_refinement ? &view->support : nullptr);
  return view;
}

/** The source seen from \a pose; the residual grid into \a pose when it has none. */
std::shared_ptr<const Viewpoint> finalViewpoint(const SourceContext& source, Pose& pose,
                                                StageTimes& times)
{
  const std::shared_ptr<const Viewpoint> view =
      pose.view ? pose.view : viewFrom(source, pose, times);
  if (pose.grid)
    return view;
  if (view->grid) {
    pose.grid = view->grid;
    pose.peak = view->peak;
  } else {
    residualGrid(source, view->H, pose, times);
  }
  return view;
}

/** The shift on the final grid and verification into \a next, the figures into
 *  \a result; false when the source left the grid. */
bool finalShift(const SourceContext& source, Pose& next, PhaserResult& result)
{
  const TargetModel& target = source.target;
  const StageParameters& params = source.params;
  const bool single = params.passes == 1;
  const SpatialSpectrum& grid = single ? target.coarse : target.fine;
  const double grid_energy = single ? target.coarse_energy : target.fine_energy;
  StageTimes& times = result.diagnostics.times;
  SpatialVolume volume;
  double energy = 0.0;
  const SpatialCorrelationResult shift = correlateTranslation(
      grid, (next.R * source.points).colwise() + next.t,
      single ? params.whitening : 0.0, params.num_threads, times, &volume, &energy);
  if (!(energy > 0.0))
    return false;
  next.t += shift.shift;
  next.verification = verifyBothWays(source, next.R, next.t, times, params.num_threads);
  result.diagnostics.translation_score = shift.score;
  const double peak = volume.values.empty()
                          ? 0.0
                          : volume.values[volume.grid.flatIndex(
                                shift.index.x(), shift.index.y(), shift.index.z())];
  const double energy_product = grid_energy * energy;
  result.diagnostics.normalized_overlap =
      energy_product > 0.0 ? peak / std::sqrt(energy_product) : 0.0;
  result.translation_covariance =
      translationCovariance(volume, shift.index, energy_product);
  return true;
}

} // namespace

SphericalSpectrum sphericalSpectrum(const Eigen::Matrix3Xd& points,
                                    const ChannelValues& channels,
                                    const PhaserParameters& params, const char* which,
                                    StageTimes& times, SphericalSupport* support)
{
  int observed = 0;
  SphericalSpectrum F = cloudSphericalSpectrum(
      points, channels, params.bandwidth, params.fusion_levels, params.num_threads,
      observed, times.sampling, times.sht, support);
  if (observed < 2)
    throw InvalidArgument(
        std::string(which) +
        " cloud has fewer than two distinct directions from its "
        "projection center (empty, all at the center, or a single point)");
  if (!(spectrumSquaredNorm(F) > 0.0))
    throw InvalidArgument(std::string(which) + " cloud is constant on the sphere");
  return F;
}

SpatialSpectrum occupancySpectrum(const SpatialGrid& grid,
                                  const Eigen::Matrix3Xd& points, int num_threads)
{
  SpatialVoxelParameters voxel;
  voxel.saturation = kOccupancySaturation;
  voxel.num_threads = num_threads;
  return computeSpectrum(voxelize(grid, points, voxel), num_threads);
}

Verification verifyBothWays(const SourceContext& source, const Eigen::Matrix3d& R,
                            const Eigen::Vector3d& t, StageTimes& times, int threads)
{
  const auto start = Clock::now();
  const StageParameters& params = source.params;
  const TargetModel& target = source.target;
  Verification verification =
      verifyPose(target.index, source.samples, R, t, threads,
                 params.viewpoints ? &target.free_space : nullptr);
  if (params.viewpoints)
    verification.reverse_free_space_violation =
        freeSpaceViolation(source.free_space, target.samples, target.sample_weights,
                           R.transpose(), -(R.transpose() * t), threads);
  times.verification += msSince(start);
  return ranked(verification);
}

SpatialCorrelationResult correlateTranslation(const SpatialSpectrum& target,
                                              const Eigen::Matrix3Xd& points,
                                              double whitening, int num_threads,
                                              StageTimes& times, SpatialVolume* volume,
                                              double* source_energy, double max_shift)
{
  const auto start = Clock::now();
  SpatialSpectrum S = occupancySpectrum(target.grid, points, num_threads);
  if (source_energy)
    *source_energy = spectrumEnergy(S);
  SpatialVolume plain;
  if (volume && whitening > 0.0)
    plain = correlateSpectra(target, S, num_threads);
  SpatialVolume C =
      correlateSpectraWhitened(target, std::move(S), whitening, num_threads);
  if (std::isfinite(max_shift))
    keepShiftsWithin(C, Eigen::Vector3d::Zero(), max_shift);
  const SpatialCorrelationResult shift = findSpatialPeak(
      C, SpatialPeakRefinement::kGaussian, num_threads, volume != nullptr);
  if (volume)
    *volume = whitening > 0.0 ? std::move(plain) : std::move(C);
  times.translation += msSince(start);
  return shift;
}

double maxShift(const SourceContext& source)
{
  const StageParameters& params = source.params;
  return params.region ? params.region->radius + source.target.coarse.grid.voxel_size
                       : std::numeric_limits<double>::infinity();
}

Pose refineOnSamples(const SourceContext& source, const Pose& pose, StageTimes& times,
                     int num_threads, bool all_samples)
{
  const auto start = Clock::now();
  const TargetModel& target = source.target;
  const RigidPose refined =
      refinePoseWithin(target.index, all_samples ? source.samples : source.polish, pose,
                       kLocalRefinementSteps, kHypothesisSeparation,
                       2.0 * target.coarse.grid.voxel_size, &target.reach_index);
  times.verification += msSince(start);
  if (refined.R == pose.R && refined.t == pose.t)
    return pose; // refused or nothing to climb: verifies as before
  Pose next = pose;
  static_cast<RigidPose&>(next) = refined;
  next.verification = verifyBothWays(source, next.R, next.t, times, num_threads);
  return next.verification.rank > pose.verification.rank ? next : pose;
}

// Each pass sees the moved source from the target's center (free of its own
// viewpoint's parallax) and composes the residual rotation and a fine-grid shift with
// the estimate; a shift below a quarter of a fine voxel: the right viewpoint, stop.
Pose reprojectionPasses(const SourceContext& source, Pose pose, int& passes,
                        StageTimes& times)
{
  const StageParameters& params = source.params;
  const double settled = 0.25 * source.target.fine.grid.voxel_size;
  for (int pass = 1; pass < params.passes; ++pass) {
    std::shared_ptr<Viewpoint> view = viewFrom(source, pose, times);
    Pose next;
    next.verifiable = pose.verifiable;
    residualGrid(source, view->H, next, times);
    const Eigen::Matrix3d dR =
        rotationFromEuler(gridEuler(next.peak, params.bandwidth));
    next.R = dR * pose.R;
    next.t = dR * pose.t;
    const Eigen::Vector3d shift =
        correlateTranslation(source.target.fine,
                             (next.R * source.points).colwise() + next.t, 0.0,
                             params.num_threads, times)
            .shift;
    next.t += shift;
    next.verification =
        verifyBothWays(source, next.R, next.t, times, params.num_threads);
    if (!improves(next, pose)) {
      view->grid = next.grid;
      view->peak = next.peak;
      pose.view = std::move(view);
      break;
    }
    pose = next;
    passes = pass + 1;
    if (shift.norm() < settled)
      break;
  }
  return pose;
}

Pose refineFinalPose(const SourceContext& source, Pose pose, bool decided,
                     PhaserResult& result)
{
  const StageParameters& params = source.params;
  StageTimes& times = result.diagnostics.times;
  const bool after_pass = pose.grid != nullptr;
  const std::shared_ptr<const Viewpoint> view = finalViewpoint(source, pose, times);
  const Eigen::Matrix3d start =
      after_pass ? Eigen::Matrix3d::Identity()
                 : rotationFromEuler(gridEuler(pose.peak, params.bandwidth));
  const std::shared_ptr<const So3CorrelationGrid> rotation_grid = pose.grid;
  const So3GridIndex peak = pose.peak;
  double value = (*rotation_grid)(peak);
  const Eigen::Matrix3d dR =
      decided ? Eigen::Matrix3d::Identity()
              : refineResidualRotation(source, *view, start, value, times);
  Pose next;
  next.verifiable = pose.verifiable;
  next.R = dR * pose.R;
  next.t = dR * pose.t;
  const bool measured = finalShift(source, next, result);
  result.diagnostics.rotation_score =
      value / (source.target.spherical_norm * std::sqrt(spectrumSquaredNorm(view->H)));
  if (measured && improves(next, pose))
    pose = next;
  if (pose.verifiable)
    pose = refineOnSamples(source, pose, times, params.num_threads, true);
  rotationSamples(*rotation_grid, peak, pose.R, result.diagnostics);
  return pose;
}

} // namespace detail
} // namespace pcl::phaser