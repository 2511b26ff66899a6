/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine (not installed): the target model, the state of one estimate
// and the stages the files of src/core/pipeline share.
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

/** Fewest verification samples (occupied cells of the verification radius) a source
 *  needs for its pose to be verified: fewer cannot tell a pose from another. */
constexpr int kMinVerificationSamples = 20;

/** Most verification samples of the source, and of the target for the reverse
 *  free-space test: an inlier share from this many has a standard error below 0.004
 *  (a LiDAR scan gives about 3,000, a volumetric cloud hundreds of thousands). */
constexpr Eigen::Index kMaxVerificationSamples = 16384;

/** How far (radians, at B = 64, scaled by 64 / B) the normalized refinement may move
 *  the rotation from the maximum of plain C; chosen on the demo pairs and the NEES
 *  study. */
constexpr double kNormalizedRefinementRadius = 0.75 * M_PI / 180.0;

/** The parameters the stages run with: the caller's, normalized_refinement off about
 *  centroids, and whether the clouds are seen from their sensor origins. */
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
  /** Binary occupancy on the whole target, padded (any shift up to half the extent),
   *  and on its inner region with little padding (the residual of later passes). */
  SpatialSpectrum coarse, fine;
  double coarse_energy = 0.0, fine_energy = 0.0; ///< spectrumEnergy of coarse and fine
  PointIndex index;                              ///< target points, for verifyPose
  PointIndex reach_index; ///< at kReachVoxels (sensor-centered only)
  double thickness = 0.0; ///< SurfacePatches::thickness of the target
  FreeSpace free_space; ///< what the target's sensor saw through (sensor-centered only)
  /** Evenly spaced target points with their orientation weights, for the reverse
   *  free-space test (sensor-centered only). */
  Eigen::Matrix3Xd samples;
  Eigen::VectorXd sample_weights;
  double preparation_ms = 0.0;
};

namespace detail {

using Clock = std::chrono::steady_clock;

/** Rotation peaks closer than this are one hypothesis (a few grid cells at B = 64). */
constexpr double kHypothesisSeparation = 10.0 * M_PI / 180.0;

/** Largest tilt (radians; any yaw) of the residual rotation a re-projection pass, or
 *  the final refinement after none, searches for: the residual of a pass-1 hypothesis
 *  is a few grid cells, so only the beta rows near the identity are correlated. */
constexpr double kResidualTilt = 20.0 * M_PI / 180.0;

/** Verification radius, in coarse voxels. */
constexpr double kVerificationVoxels = 0.5;

/** Radius, in coarse voxels, of the index the local refinement takes its first step
 *  against: a coarse translation peak can be a voxel off, twice the verification
 *  radius, and the few samples then within it (the ground) can walk the climb away. */
constexpr double kReachVoxels = 1.0;

/** The verification index and pass-1 occupancy keep one point per cube of their
 *  radius (voxel) / kIndexThinning. */
constexpr double kIndexThinning = 8.0;

/** Direction cells of the free-space test (1.4 deg) and its margin in coarse voxels. */
constexpr int kFreeSpaceBandwidth = 128;
constexpr double kFreeSpaceMargin = 1.0;

/** Inlier share one hypothesis at least must reach for verification to rank them. */
constexpr double kMinRankingInliers = 0.1;
/** Among hypotheses outside the verification limits, those with at least this share of
 *  the most inliers any hypothesis has rank above the others. */
constexpr double kMinSupport = 0.5;

/** Largest surface thickness, in verification radii, at which poses are verified. */
constexpr double kMaxThickness = 1.0 / 3.0;

/** Weight of a free-space violation (of either sensor) against an inlier in the rank.
 */
constexpr double kViolationWeight = 6.0;

/** The final pose is distinct from the runner-up when its rank exceeds that one's by
 *  more than this many standard errors: the one-sided 99 % point of a normal. */
constexpr double kDistinctErrors = 2.33;

/** Saturation of the occupancy grids: binary occupancy, so the near-sensor density
 *  does not vote for stacking the sensors. */
constexpr double kOccupancySaturation = 0.05;

/** Patches of the orientation histogram, in coarse voxels. */
constexpr double kPatchVoxels = 1.0;

/** When the pass-1 choice would not be claimed: the translation peaks beyond the
 *  highest that each pass-1 rotation adds, their least separation in coarse voxels,
 *  and the orientation peaks beyond the orientation candidates that become hypotheses
 *  (a scene of orthogonal walls has near-equal peaks at its symmetric orientations, and
 *  on a partial view the right one ranked below ten of them). */
constexpr int kExtraTranslationPeaks = 2;
constexpr int kPeakSeparation = 3;
constexpr int kSpareOrientationPeaks = 10;

/** Gauss-Newton steps of the local refinement on the verification samples. */
constexpr int kLocalRefinementSteps = 10;

/** The source seen from a pose's viewpoint: its spectrum (with its support when the
 *  normalized refinement needs it) and the residual rotation grid with its peak. */
struct Viewpoint {
  SphericalSpectrum H;
  SphericalSupport support;
  std::shared_ptr<const So3CorrelationGrid> grid;
  So3GridIndex peak{};
};

/** A pose (centered coordinates) and how it verifies; with the rotation grid of the
 *  last accepted re-projection pass (its peak near the identity), if any. */
struct Pose : RigidPose {
  Verification verification;
  std::shared_ptr<const So3CorrelationGrid> grid;
  So3GridIndex peak{};
  bool verifiable = false; ///< hypotheses and passes are ranked by verification
  /** What a refused re-projection pass measured from this pose's own viewpoint. */
  std::shared_ptr<const Viewpoint> view;
};

/** Everything one estimate needs about the source. */
struct SourceContext {
  const TargetModel& target;
  const Eigen::Matrix3Xd& points;
  const ChannelValues& channels;
  const StageParameters& params;
  VerificationSamples samples; ///< evenly spaced source points for verifyPose
  SurfacePatches patches;      ///< planar patches of the source (coarse voxels)
  FreeSpace free_space;        ///< what the source's sensor saw through
  /** The points thinned to one (the centroid) per kIndexThinning-th of a coarse voxel,
   *  for the pass-1 occupancy grids: binary, so they barely change. */
  Eigen::Matrix3Xd coarse_points;
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

double msSince(Clock::time_point start);

/** The source's spherical spectrum, its time into \a times; with its support when
 *  \a support is given. \throws InvalidArgument when it carries no spherical signal */
SphericalSpectrum sourceSpectrum(const Eigen::Matrix3Xd& points,
                                 const ChannelValues& channels,
                                 const PhaserParameters& params, StageTimes& times,
                                 SphericalSupport* support = nullptr);

/** Binary occupancy spectrum of \a points on \a grid. */
SpatialSpectrum occupancySpectrum(const SpatialGrid& grid,
                                  const Eigen::Matrix3Xd& points, int num_threads);

/** Pass 1: every rotation hypothesis through the coarse translation search,
 *  verification and local refinement, and the best of them (by verification where
 *  poses can be verified, else the range peak that overlaps most). */
GlobalSearch globalSearch(const SourceContext& source,
                          const So3CorrelationGrid& correlation, double source_norm,
                          StageTimes& times);

/** Later passes from the viewpoint of \a pose, kept while they verify better;
 *  \a passes counts those run. */
Pose reprojectionPasses(const SourceContext& source, Pose pose, int& passes,
                        StageTimes& times);

/** The final rotation refinement and shift, kept when they verify better, and the
 *  local refinement; their scores, translation covariance and rotation samples (the
 *  uncertainty) into \a result. */
Pose refineFinalPose(const SourceContext& source, Pose pose, PhaserResult& result);

/** \a measured with its rank: score less kViolationWeight x both free-space
 *  violations. */
Verification ranked(const PoseVerification& measured);

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

/** The final \a pose's verification, runner-up and fit covariance into \a result, and
 *  whether it is verified, against result.diagnostics.hypotheses. */
void judgeFinalPose(const SourceContext& source, const Pose& pose,
                    PhaserResult& result);

/** Prepares a target whose points are relative to its projection center.
 *  \throws InvalidArgument when the points carry no spherical signal */
std::shared_ptr<const TargetModel> prepareTarget(const Eigen::Matrix3Xd& points,
                                                 const StageParameters& params,
                                                 const ChannelValues& channels);

/** Registers a source (points relative to its projection center) against a target
 *  model prepared with \a params: the stages in centered coordinates. Returns the
 *  final pose; fills everything of \a result but the caller-frame fields.
 *  \throws InvalidArgument when the source carries no spherical signal */
RigidPose estimateCentered(const TargetModel& target, const Eigen::Matrix3Xd& points,
                           const StageParameters& params, const ChannelValues& channels,
                           PhaserResult& result);

} // namespace detail
} // namespace pcl::phaser
