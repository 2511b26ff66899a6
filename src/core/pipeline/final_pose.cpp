/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The final pose: the residual rotation refined, the last shift, the local refinement,
 * and the figures the uncertainty is made of.
 */
#include "pipeline/final_pose.h"
#include "pipeline/passes.h"
#include "pipeline/stage_tasks.h"
#include "pipeline/translation_search.h"
#include "uncertainty/peak_neighborhood.h"

#include <algorithm>
#include <cmath>

namespace pcl::phaser::detail {
namespace {

/** How far (at B = 64, scaled by 64 / B) the normalized refinement may move from the
 *  maximum of plain C; chosen on the demo pairs and the NEES study. */
constexpr double kNormalizedRefinementRadius = 0.75 * M_PI / 180.0;

/** Newton refinement of \a R on C, then on the energy-normalized correlation (plain C
 *  leans towards equal sensor tilt); the exact C at the result into \a value. */
Eigen::Matrix3d refineResidualRotation(const SourceContext& source,
                                       const Viewpoint& view, const Eigen::Matrix3d& R,
                                       double& value, StageTimes& times)
{
  const auto start = Clock::now();
  const StageSettings& settings = source.settings;
  const TargetModel& target = source.target;
  RefinedRotation refined = refineRotation(
      target.spherical, view.H, R, settings.params.bandwidth,
      settings.params.refinement_iterations, settings.params.num_threads);
  if (settings.params.normalized_refinement)
    refined = refineRotation(
        target.spherical, view.H, refined.rotation, settings.params.bandwidth,
        settings.params.refinement_iterations, settings.params.num_threads,
        &target.spherical_support, &view.support,
        kNormalizedRefinementRadius * 64.0 / settings.params.bandwidth);
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
  const StageSettings& settings = source.settings;
  const bool single = settings.params.passes == 1;
  const SpatialSpectrum& grid = single ? target.coarse : target.fine;
  const double grid_energy = single ? target.coarse_energy : target.fine_energy;
  StageTimes& times = result.diagnostics.times;
  SpatialVolume volume;
  double energy = 0.0;
  const SpatialCorrelationResult shift =
      correlateTranslation(grid, (next.R * source.points).colwise() + next.t,
                           single ? settings.params.whitening : 0.0,
                           settings.params.num_threads, times, &volume, &energy);
  if (!(energy > 0.0))
    return false;
  next.t += shift.shift;
  next.verification = verificationOf(source, next, times, settings.params.num_threads);
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

Pose refineFinalPose(const SourceContext& source, Pose pose, bool decided,
                     PhaserResult& result)
{
  const StageSettings& settings = source.settings;
  StageTimes& times = result.diagnostics.times;
  const bool after_pass = pose.grid != nullptr;
  const std::shared_ptr<const Viewpoint> view = finalViewpoint(source, pose, times);
  const Eigen::Matrix3d start =
      after_pass ? Eigen::Matrix3d::Identity()
                 : rotationFromEuler(gridEuler(pose.peak, settings.params.bandwidth));
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
    pose = refinedOnSamples(source, pose, times, settings.params.num_threads, true);
  rotationSamples(*rotation_grid, peak, pose.R, result.diagnostics);
  return pose;
}

} // namespace pcl::phaser::detail
