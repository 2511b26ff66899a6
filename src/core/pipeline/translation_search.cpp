/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Translations by occupancy correlation: pass 1's hypotheses on the coarse grid, each
 * verified and refined, and the extra peaks of the widened search.
 */
#include "pipeline/cloud_spectra.h"
#include "pipeline/pose.h"
#include "pipeline/stage_tasks.h"
#include "pipeline/translation_search.h"
#include "priors/region.h"
#include "uncertainty/peak_neighborhood.h"

#include <cmath>

namespace pcl::phaser::detail {
namespace {

/** When the choice would not be claimed: the translation peaks each rotation adds and
 *  their separation (coarse voxels). */
constexpr int kExtraTranslationPeaks = 2;
constexpr int kPeakSeparation = 3;

/** The pose (R, t) with its verification (one thread). */
Pose verifiedPose(const SourceContext& source, const RigidPose& rigid,
                  StageTimes& times)
{
  Pose pose;
  static_cast<RigidPose&>(pose) = rigid;
  pose.verification = verificationOf(source, rigid, times, 1);
  return pose;
}

void record(Hypothesis& h, const Pose& pose)
{
  h.rotation = pose.R;
  h.translation = pose.t;
  h.verification = pose.verification;
}

/** The priors' bound on pass 1's shifts (AllowedPoses::shiftBound). */
double shiftBound(const SourceContext& source)
{
  return source.allowed.shiftBound(source.target.coarse.grid.voxel_size);
}

/** Pass 1's whitened correlation of the source turned by \a R with the coarse target,
 *  in single precision (one thread), its shifts kept within the priors' bound. */
SpatialVolumeF coarseCorrelation(const SourceContext& source, const Eigen::Matrix3d& R)
{
  const TargetModel& target = source.target;
  SpatialVolumeF C = correlateSpectraWhitened(
      target.coarse_single,
      occupancySpectrumSingle(target.coarse.grid, R * source.coarse_points, 1),
      source.settings.params.whitening, 1);
  const double max_shift = shiftBound(source);
  if (std::isfinite(max_shift))
    keepShiftsWithin(C, Eigen::Vector3d::Zero(), max_shift);
  return C;
}

/** runTasks of \a task(k, its times); the wall time into \a times in their proportions.
 */
template <typename Task>
void runTimed(const SourceContext& source, std::size_t n, StageTimes& times,
              const Task& task)
{
  std::vector<StageTimes> task_times(n);
  const auto start = Clock::now();
  runTasks(static_cast<int>(n), source.settings.params.num_threads, [&](int k) {
    task(static_cast<std::size_t>(k), task_times[static_cast<std::size_t>(k)]);
  });
  const double wall = msSince(start);
  double translation = 0.0, verification = 0.0;
  for (const StageTimes& task : task_times) {
    translation += task.translation;
    verification += task.verification;
  }
  const double busy = translation + verification;
  times.translation += busy > 0.0 ? wall * translation / busy : 0.0;
  times.verification += busy > 0.0 ? wall * verification / busy : 0.0;
}

} // namespace

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

void translateHypotheses(const SourceContext& source,
                         std::vector<Hypothesis>& hypotheses, StageTimes& times,
                         std::size_t first)
{
  const bool refined = source.canVerify();
  runTimed(source, hypotheses.size() - first, times,
           [&](std::size_t k, StageTimes& task) {
             Hypothesis& h = hypotheses[first + k];
             const auto begin = Clock::now();
             const SpatialCorrelationResult shift =
                 findSpatialPeak(coarseCorrelation(source, h.rotation));
             task.translation += msSince(begin);
             h.overlap = shift.peak_value;
             const Pose pose = verifiedPose(source, {h.rotation, shift.shift}, task);
             record(h, refined ? refinedOnSamples(source, pose, task, 1) : pose);
           });
}

void addTranslationPeaks(const SourceContext& source,
                         const std::vector<Eigen::Matrix3d>& rotations,
                         std::vector<Hypothesis>& hypotheses, StageTimes& times)
{
  const std::size_t n = rotations.size();
  std::vector<std::vector<Pose>> extra(n);
  runTimed(source, n, times, [&](std::size_t k, StageTimes& task) {
    const auto begin = Clock::now();
    const Eigen::Matrix3d& R = rotations[k];
    // The pass-1 correlation again: cheaper than keeping every volume (8 MB each).
    std::vector<SpatialCorrelationResult> peaks = findDistinctSpatialPeaks(
        coarseCorrelation(source, R), 1 + kExtraTranslationPeaks, kPeakSeparation);
    task.translation += msSince(begin);
    for (std::size_t j = 1; j < peaks.size(); ++j)
      extra[k].push_back(refinedOnSamples(
          source, verifiedPose(source, {R, peaks[j].shift}, task), task, 1));
  });
  for (std::size_t k = 0; k < n; ++k)
    for (const Pose& pose : extra[k]) {
      Hypothesis h = hypotheses[k];
      record(h, pose);
      hypotheses.push_back(h);
    }
}

} // namespace pcl::phaser::detail
