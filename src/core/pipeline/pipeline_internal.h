/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine (not installed): the target model, the state of one estimate
// and the stages pipeline.cpp and pipeline_stages.cpp share.
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
 *  free-space test: an inlier share from this many has a standard error below 0.004,
 *  while a volumetric cloud (one sample per occupied cell of the radius) could give
 *  hundreds of thousands, each looked up in every verification and polish sweep. A
 *  LiDAR scan gives about 3,000, a Kinect frame 15,000. */
constexpr Eigen::Index kMaxVerificationSamples = 16384;

/** How far (radians, at B = 64, scaled by 64 / B) the normalized refinement may move
 * the rotation from the maximum of plain C; the radius was chosen on the demo pairs and
 *  the NEES study (doc/benchmarks.md section 10). */
constexpr double kNormalizedRefinementRadius = 0.75 * M_PI / 180.0;

/** The trust radius (radians) at bandwidth B: kNormalizedRefinementRadius * 64 / B. */
inline double normalizedRefinementRadius(int bandwidth)
{
  return kNormalizedRefinementRadius * 64.0 / bandwidth;
}

/** The stages fill the centered-frame fields of the result, align() the caller-frame
 *  ones; the old name of the result is kept for pipeline_stages.cpp only. */
using PhaserEstimate = PhaserResult;

/** The parameters the stages run with: the caller's, with normalized_refinement off
 *  about centroids, and whether the clouds are seen from their sensor origins (then
 *  hypotheses are ranked by verifyPose, including the samples in space the target saw
 *  through, and the orientation histograms add hypotheses). */
struct StageParameters : PhaserParameters {
  bool sensor_centered = true;
};

class TargetModel {
public:
  StageParameters params;
  std::size_t channels = 0; ///< number of fused channels beyond the geometry
  SphericalSpectrum spherical;
  SphericalSupport spherical_support; ///< for the normalized refinement
  double spherical_norm = 0.0;
  SphericalSpectrum orientation; ///< surface-orientation histogram (may be empty)
  /** Binary occupancy on the whole target, padded (any shift up to half the extent),
   *  and on its inner region with little padding (the residual of later passes). */
  SpatialSpectrum coarse, fine;
  double coarse_energy = 0.0, fine_energy = 0.0; ///< spectrumEnergy of coarse and fine
  PointIndex index;                              ///< target points, for verifyPose
  /** The target points at a coarse voxel's radius (kPolishReachVoxels): the first step
   *  of every polish matches against it (sensor-centered only). */
  PointIndex reach_index;
  double thickness = 0.0; ///< SurfacePatches::thickness of the target
  FreeSpace free_space; ///< what the target's sensor saw through (sensor-centered only)
  /** Evenly spaced target points with their orientation weights: the reverse
   *  free-space test, against what the source's sensor saw (sensor-centered only). */
  Eigen::Matrix3Xd samples;
  Eigen::VectorXd sample_weights;
  double preparation_ms = 0.0;
};

namespace detail {

using Clock = std::chrono::steady_clock;

/** Rotation peaks closer than this are one hypothesis (a few grid cells at B = 64). */
constexpr double kHypothesisSeparation = 10.0 * M_PI / 180.0;

/** Largest tilt (radians; any yaw) of the residual rotation a re-projection pass, or
 *  the final stage after none, searches for: the residual of a pass-1 hypothesis is a
 *  few grid cells, so only the beta rows near the identity are correlated (about a
 *  sixth of the SO(3) grid at B = 64). */
constexpr double kResidualTilt = 20.0 * M_PI / 180.0;

/** Verification radius, in coarse voxels. */
constexpr double kVerificationVoxels = 0.5;

/** Radius, in coarse voxels, of the index the polish takes its first step against. A
 *  coarse translation peak can be a voxel off, twice the verification radius: most
 *  samples then have no target point within that radius, and the few that do (the
 *  ground) can walk the climb away from the truth (benchmarks.md 9.21). */
constexpr double kPolishReachVoxels = 1.0;

/** The verification index keeps one point per cube of its radius / kIndexThinning;
 *  the pass-1 occupancy one per cube of a coarse voxel / kIndexThinning. */
constexpr double kIndexThinning = 8.0;

/** Direction cells of the free-space test (about 1.4 deg) and its margin in coarse
 *  voxels. */
constexpr int kFreeSpaceBandwidth = 128;

constexpr double kFreeSpaceMargin = 1.0;

/** Inlier share one hypothesis at least must reach for verification to rank them. */
constexpr double kMinRankingInliers = 0.1;
/** Among hypotheses outside the verification limits, those with at least this share of
 *  the most inliers any hypothesis has rank above the others. */
constexpr double kMinSupport = 0.5;

/** Largest surface thickness, in verification radii, at which poses are verified. */
constexpr double kMaxThickness = 1.0 / 3.0;

/** Weight of a free-space violation (of either sensor) against an inlier in rank(). */
constexpr double kViolationWeight = 6.0;

/** The final pose counts as distinct from the best other hypothesis when its rank
 *  exceeds that one's by more than this many standard errors of the difference
 *  (PhaserResult::runner_up_error): the one-sided 99 % point of a normal. */
constexpr double kDistinctErrors = 2.33;

/** Saturation of the occupancy grids: a voxel with a fraction of a point's weight is
 *  already almost full, so occupancy is binary and the near-sensor density (each scan
 *  is densest around its own sensor) does not vote for stacking the sensors. */
constexpr double kOccupancySaturation = 0.05;

/** Patches of the orientation histogram, in coarse voxels. */
constexpr double kPatchVoxels = 1.0;

/** Translation peaks beyond the highest that each pass-1 rotation contributes when the
 *  pass-1 choice misses the verification limits or does not stand out (standsOut), and
 *  their least separation in coarse voxels. */
constexpr int kExtraTranslationPeaks = 2;
/** Peaks of the orientation histograms' correlation beyond the orientation candidates
 *  that become hypotheses of their own in that case too: a scene of orthogonal walls
 *  and ground has near-equal peaks at its 90, 120 and 180 deg symmetric orientations,
 *  and on a partial view the right one can rank below ten of them (benchmarks.md
 *  9.19). */
constexpr int kSpareOrientationPeaks = 10;
constexpr int kPeakSeparation = 3;

/** Gauss-Newton steps of refinePose on the final pose. */
constexpr int kPolishIterations = 10;

/** The source seen from a pose's viewpoint: its spectrum (with its support when the
 *  normalized refinement needs it) and the residual rotation grid with its peak. */
struct Viewpoint {
  SphericalSpectrum H;
  SphericalSupport support;
  std::shared_ptr<const So3CorrelationGrid> grid;
  So3GridIndex peak{};
};

/** A pose and how well it verifies; with the rotation grid of the last accepted
 *  re-projection pass (its peak is near the identity), if one was accepted. */
struct Pose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  PoseVerification v;
  std::shared_ptr<const So3CorrelationGrid> grid;
  So3GridIndex peak{};
  bool verifiable = false; ///< hypotheses and passes are ranked by verification
  /** What a refused re-projection pass measured from this pose's own viewpoint: the
   *  final stage starts from it instead of measuring it again. */
  std::shared_ptr<const Viewpoint> view;
};

/** Everything one estimate needs about the source. */
struct SourceContext {
  const TargetModel& target;
  const Eigen::Matrix3Xd& points;
  const ChannelValues& channels;
  const StageParameters& p;
  VerificationSamples samples; ///< evenly spaced source points for verifyPose
  SurfacePatches patches;      ///< planar patches of the source (coarse voxels)
  FreeSpace free_space;        ///< what the source's sensor saw through
  /** The points thinned to one (the centroid) per kIndexThinning-th of a coarse voxel:
   *  the pass-1 occupancy grids are binary, so they barely change, at a fraction of
   *  the cost of rotating and voxelizing every point per hypothesis. */
  Eigen::Matrix3Xd coarse_points;
};

/** \a task(k) for k = 0 .. count - 1 as independent one-thread tasks (parallelFor, one
 *  task per chunk: a thread the scheduler parks delays only its own task); the first
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

/** The source's spherical spectrum, timed; with its support when \a support is given.
 */
SphericalSpectrum sourceSpectrum(const Eigen::Matrix3Xd& points,
                                 const ChannelValues& channels,
                                 const PhaserParameters& p, PhaserResult& e,
                                 SphericalSupport* support = nullptr);

/** The global search: C on the SO(3) grid. */
So3CorrelationGrid correlateRotation(const TargetModel& target,
                                     const SphericalSpectrum& H,
                                     const PhaserParameters& p, PhaserResult& e);

/** Newton refinement of \a R on C, timed; with PhaserParameters::normalized_refinement
 *  then on the energy-normalized correlation (see refineRotation: plain C leans towards
 *  equal sensor tilt) near that maximum, with the supports given. Returns the exact C
 *  at the result through \a value. */
Eigen::Matrix3d refine(const TargetModel& target, const SphericalSpectrum& H,
                       const SphericalSupport& support, const Eigen::Matrix3d& R,
                       const PhaserParameters& p, double& value, PhaserResult& e);

/** Correlation peak over the norms of the two grids (0 when one is empty). */
double normalizedPeak(double peak, double energy_product);

/** Grid samples around a peak as rotations of the final estimate: each sample's offset
 *  from the peak, delta_i = R_i R_peak^T, applied on the left of \a estimate (so the
 *  spread is expressed in the target frame), with weights from the correlation above
 * the lowest value of the block. */
void rotationSamples(const So3CorrelationGrid& C, const So3GridIndex& peak,
                     const Eigen::Matrix3d& estimate, PhaserResult& e);

/** Binary occupancy spectrum of \a points on \a grid. */
SpatialSpectrum occupancySpectrum(const SpatialGrid& grid,
                                  const Eigen::Matrix3Xd& points, int num_threads);

double volumeAt(const SpatialVolume& v, const Eigen::Vector3i& i);

/** Translation of the (already rotated) \a points onto \a target by the occupancy
 *  correlation, whitened by \a whitening (correlateSpectraWhitened), sub-voxel peak.
 *  When \a volume is given (the final stage), the plain correlation volume is kept for
 *  the covariance and the peak's sidelobe score is computed. */
SpatialCorrelationResult shiftOf(const SpatialSpectrum& target,
                                 const Eigen::Matrix3Xd& points, double whitening,
                                 const PhaserParameters& p, PhaserResult& e,
                                 SpatialVolume* volume = nullptr,
                                 double* source_energy = nullptr);

/** Pass 1: every hypothesis through the coarse translation search and verification;
 *  see pipeline_stages.cpp for the ranking. */
Pose globalSearch(const SourceContext& s, const So3CorrelationGrid& C, double h_norm,
                  PhaserResult& e);

/** Later passes from the viewpoint of the estimate, kept while they verify no worse. */
Pose reprojectionPasses(const SourceContext& s, Pose pose, PhaserResult& e);

/** How a verified pose ranks (pipeline_verdict.cpp): the closeness-weighted inlier
 *  share less kViolationWeight x both free-space violations. */
double rank(const PoseVerification& v);

/** Whether \a v meets the verification limits of \a p (pipeline_verdict.cpp). */
bool meetsLimits(const PoseVerification& v, const PhaserParameters& p);

/** How the pose compared with the best hypothesis distinct from it (standsOut). */
struct Distinctness {
  bool stands_out = true; ///< true when no hypothesis is distinct
  double runner_up_rank = -std::numeric_limits<double>::infinity(); ///< its rank
  double error = 0.0; ///< standard error of the rank difference (sensor origins)
};

/** Whether \a pose (its verification set) outranks the best hypothesis distinct from it
 *  by more than kDistinctErrors standard errors of the difference (about centroids, the
 *  difference alone; pipeline_verdict.cpp). */
Distinctness standsOut(const SourceContext& s, const Pose& pose,
                       const std::vector<RotationHypothesis>& hypotheses);

/** The final \a pose, its verification figures and its covariance (fitCovariance) into
 *  \a e, and whether it is verified (pipeline_verdict.cpp). */
void verdict(const SourceContext& s, const Pose& pose, PhaserResult& e);

/** The final refinement, shift, uncertainty and verification decision, into \a e. */
void finalStage(const SourceContext& s, Pose pose, PhaserResult& e);

/** Prepares a target whose points are relative to its projection center.
 *  \throws InvalidArgument when the points carry no spherical signal (all at the
 *  center, or all in one direction) */
std::shared_ptr<const TargetModel> prepareTarget(const Eigen::Matrix3Xd& points,
                                                 const StageParameters& params,
                                                 const ChannelValues& channels);

/** Registers a source (points relative to its projection center) against a target
 *  model prepared with \a p: the stages of one estimate, in centered coordinates.
 *  \throws InvalidArgument when the source carries no spherical signal */
PhaserResult estimateCentered(const TargetModel& target, const Eigen::Matrix3Xd& points,
                              const StageParameters& p, const ChannelValues& channels);

} // namespace detail
} // namespace pcl::phaser
