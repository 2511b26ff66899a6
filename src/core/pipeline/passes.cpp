/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The later passes: the moved source seen from the target's center, its residual
 * rotation and a fine-grid shift.
 */
#include "pipeline/cloud_spectra.h"
#include "pipeline/passes.h"
#include "pipeline/stage_tasks.h"
#include "pipeline/translation_search.h"
#include "so3/so3_correlation.h"

namespace pcl::phaser::detail {
namespace {

/** Largest tilt of the residual rotation: a pass-1 residual is a few cells. */
constexpr double kResidualTilt = 20.0 * M_PI / 180.0;

} // namespace

std::shared_ptr<Viewpoint> viewFrom(const SourceContext& source, const RigidPose& pose,
                                    StageTimes& times)
{
  const StageSettings& settings = source.settings;
  auto view = std::make_shared<Viewpoint>();
  view->H = sphericalSpectrum(
      (pose.R * source.points).colwise() + pose.t, source.channels, settings,
      settings.params.num_threads, "source", times,
      settings.params.normalized_refinement ? &view->support : nullptr);
  return view;
}

void residualGrid(const SourceContext& source, const SphericalSpectrum& H, Pose& pose,
                  StageTimes& times)
{
  const auto start = Clock::now();
  const StageSettings& settings = source.settings;
  const int rows = betaRowsForTilt(settings.params.bandwidth, kResidualTilt);
  auto C = std::make_shared<So3CorrelationGrid>(
      So3Correlator::instance(settings.params.bandwidth)
          ->correlate(source.target.spherical, H, settings.params.num_threads, rows));
  times.so3 += msSince(start);
  pose.peak = pose.verifiable ? C->argmaxNearIdentity(kHypothesisSeparation)
                              : C->argmax(settings.params.num_threads);
  pose.grid = std::move(C);
}

// Each pass sees the moved source from the target's center (free of its own
// viewpoint's parallax) and composes the residual rotation and a fine-grid shift with
// the estimate; a shift below a quarter of a fine voxel: the right viewpoint, stop.
Pose reprojectionPasses(const SourceContext& source, Pose pose, int& passes,
                        StageTimes& times)
{
  const StageSettings& settings = source.settings;
  const double settled = 0.25 * source.target.fine.grid.voxel_size;
  for (int pass = 1; pass < settings.params.passes; ++pass) {
    std::shared_ptr<Viewpoint> view = viewFrom(source, pose, times);
    Pose next;
    next.verifiable = pose.verifiable;
    residualGrid(source, view->H, next, times);
    const Eigen::Matrix3d dR =
        rotationFromEuler(gridEuler(next.peak, settings.params.bandwidth));
    next.R = dR * pose.R;
    next.t = dR * pose.t;
    const Eigen::Vector3d shift =
        correlateTranslation(source.target.fine,
                             (next.R * source.points).colwise() + next.t, 0.0,
                             settings.params.num_threads, times)
            .shift;
    next.t += shift;
    next.verification =
        verificationOf(source, next, times, settings.params.num_threads);
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

} // namespace pcl::phaser::detail
