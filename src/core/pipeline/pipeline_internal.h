/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: the target model, the state of one estimate, the stages.
#include "channels/cloud_signals.h"
#include "channels/surface_orientation.h"
#include "so3/so3_correlation.h"
#include "so3/so3_refinement.h"
#include "spatial/spatial_correlation.h"
#include "sphere/spherical_harmonics.h"
#include "sphere/spherical_sampling.h"
#include "support/error.h"
#include "support/parallel.h"
#include "uncertainty/peak_neighborhood.h"
#include "uncertainty/pose_covariance.h"
#include "verification/pose_refinement.h"
#include "verification/verification.h"

#include <pcl_phaser/core/pipeline.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace pcl::phaser {

/** The parameters the stages run with and whether the clouds are sensor-centered. */
struct StageParameters : PhaserParameters {
  bool sensor_centered = true;
};

class TargetModel {
public:
  StageParameters params;
  SphericalSpectrum spherical;
  SphericalSupport spherical_support; ///< for the normalized refinement
  double spherical_norm = 0.0;
  SphericalSpectrum orientation; ///< surface-orientation histogram (may be empty)
  SpatialSpectrum coarse, fine;  ///< occupancy: padded whole target; inner region
  double coarse_energy = 0.0, fine_energy = 0.0; ///< spectrumEnergy of coarse and fine
  PointIndex index;                              ///< target points, for verifyPose
  PointIndex reach_index; ///< at kReachVoxels (sensor-centered only)
  double thickness = 0.0; ///< SurfacePatches::thickness of the target
  FreeSpace free_space; ///< what the target's sensor saw through (sensor-centered only)
  Eigen::Matrix3Xd samples; ///< for the reverse free-space test (sensor-centered only)
  Eigen::VectorXd sample_weights;
  double preparation_ms = 0.0;
};

namespace detail {

using Clock = std::chrono::steady_clock;

/** Rotation peaks closer than this are one hypothesis (a few grid cells at B = 64). */
constexpr double kHypothesisSeparation = 10.0 * M_PI / 180.0;

struct Viewpoint; ///< the source seen from a pose (pipeline_stages.cpp)

/** A pose (centered coordinates), how it verifies, the last accepted pass's grid. */
struct Pose : RigidPose {
  Verification verification;
  std::shared_ptr<const So3CorrelationGrid> grid;
  So3GridIndex peak{};
  bool verifiable = false; ///< hypotheses and passes are ranked by verification
  std::shared_ptr<const Viewpoint> view; ///< what a refused pass measured from here
};

/** Everything one estimate needs about the source. */
struct SourceContext {
  const TargetModel& target;
  const Eigen::Matrix3Xd& points;
  const ChannelValues& channels;
  const StageParameters& params;
  VerificationSamples samples;    ///< evenly spaced source points for verifyPose
  SurfacePatches patches;         ///< planar patches of the source (coarse voxels)
  FreeSpace free_space;           ///< what the source's sensor saw through
  Eigen::Matrix3Xd coarse_points; ///< thinned for the pass-1 (binary) occupancy grids
};

/** What pass 1 found: every hypothesis, verified, and the one chosen with its pose. */
struct GlobalSearch {
  std::vector<Hypothesis> hypotheses;
  int chosen = 0;
  Pose pose;
};

/** \a task(k) for k = 0 .. count - 1 as independent one-thread tasks; the first
 *  exception is rethrown when the others have ended. */
template <typename Task>
void runTasks(int count, int num_threads, const Task& task)
{
  parallelFor(count, 1, std::min(num_threads, count),
              [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
                for (std::ptrdiff_t k = first; k < last; ++k)
                  task(static_cast<int>(k));
              });
}

// pipeline.cpp
double msSince(Clock::time_point start);
/** The fused spherical spectrum (with \a support if given) of the \a which cloud.
 *  \throws InvalidArgument when the cloud carries no spherical signal */
SphericalSpectrum sphericalSpectrum(const Eigen::Matrix3Xd& points,
                                    const ChannelValues& channels,
                                    const PhaserParameters& params, const char* which,
                                    StageTimes& times,
                                    SphericalSupport* support = nullptr);
/** Binary occupancy spectrum of \a points on \a grid. */
SpatialSpectrum occupancySpectrum(const SpatialGrid& grid,
                                  const Eigen::Matrix3Xd& points, int num_threads);

// pipeline_stages.cpp
/** Verification of (R, t) on \a threads threads, both ways (reverse: sensor origins).
 */
Verification verifyBothWays(const SourceContext& source, const Eigen::Matrix3d& R,
                            const Eigen::Vector3d& t, StageTimes& times, int threads);
/** Translation of \a points onto \a target at the whitened correlation's sub-voxel
 *  peak, no longer than \a max_shift; with \a volume the plain correlation kept and
 *  the sidelobe score computed. */
SpatialCorrelationResult
correlateTranslation(const SpatialSpectrum& target, const Eigen::Matrix3Xd& points,
                     double whitening, int num_threads, StageTimes& times,
                     SpatialVolume* volume = nullptr, double* source_energy = nullptr,
                     double max_shift = std::numeric_limits<double>::infinity());
/** The longest pass-1 shift: the region's radius and a coarse voxel (the sensor sits
 *  at the centered origin), else unbounded. */
double maxShift(const SourceContext& source);
/** \a pose refined on the verification samples (refinePoseWithin: within the
 *  hypothesis separation and two coarse voxels), kept when it ranks higher. */
Pose refineOnSamples(const SourceContext& source, const Pose& pose, StageTimes& times,
                     int num_threads);
/** Later passes from \a pose's viewpoint, kept while they verify better (\a passes). */
Pose reprojectionPasses(const SourceContext& source, Pose pose, int& passes,
                        StageTimes& times);
/** The final rotation refinement and shift (kept when they verify better) and the local
 *  refinement; scores, translation covariance and rotation samples into \a result. */
Pose refineFinalPose(const SourceContext& source, Pose pose, PhaserResult& result);

/** Pass 1 (global_search.cpp): all hypotheses translated, verified, refined; the best.
 */
GlobalSearch globalSearch(const SourceContext& source,
                          const So3CorrelationGrid& correlation, double source_norm,
                          StageTimes& times);

// pipeline_verdict.cpp
/** \a measured with its rank: score less kViolationWeight x both violations. */
Verification ranked(const Verification& measured);
/** Whether \a verification meets the verification limits of \a params. */
bool meetsLimits(const Verification& verification, const PhaserParameters& params);

/** How the pose compared with the best hypothesis distinct from it. */
struct Distinctness {
  bool stands_out = true; ///< true when no hypothesis is distinct
  double runner_up_rank = -std::numeric_limits<double>::infinity();
  double error = 0.0; ///< standard error of the rank difference (sensor origins)
};

/** Whether \a pose outranks the best hypothesis distinct from it by more than
 *  kDistinctErrors standard errors of the difference. */
Distinctness standsOut(const SourceContext& source, const Pose& pose,
                       const std::vector<Hypothesis>& hypotheses);
/** The final \a pose's verification, runner-up, fit covariance and verdict into
 *  \a result (against its hypotheses). */
void judgeFinalPose(const SourceContext& source, const Pose& pose,
                    PhaserResult& result);

// pipeline.cpp
/** Prepares a target whose points are relative to its projection center. */
std::shared_ptr<const TargetModel> prepareTarget(const Eigen::Matrix3Xd& points,
                                                 const StageParameters& params,
                                                 const ChannelValues& channels);
/** The stages in centered coordinates (source points relative to its projection
 *  center): the final pose; everything of \a result but the caller-frame fields. */
RigidPose estimateCentered(const TargetModel& target, const Eigen::Matrix3Xd& points,
                           const StageParameters& params, const ChannelValues& channels,
                           PhaserResult& result);

} // namespace detail
} // namespace pcl::phaser
