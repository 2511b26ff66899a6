/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: the target model and the state of one estimate, shared by
// the stages (estimate.h, global_search.h, pipeline_stages.h, pipeline_verdict.h).
#include "channels/cloud_signals.h"
#include "channels/spectral_magnitude.h"
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
  /** The target's center is where its sensor stood (not an object's frame origin):
   *  the free-space test of source samples applies; else the clouds are objects, and
   *  the magnitude hypotheses join the search. */
  bool viewpoints = true;
  /** So is the source's (with viewpoints): the reverse free-space test applies. */
  bool source_viewpoint = true;
  /** Poses are chosen and claimed by verification; about centroids of clouds with about
   *  one point per verification cube (sparser than its radius) the peak rule decides.
   */
  bool verification = true;
  /** Verified without free space: objects, about their frame origin or centroid. */
  bool objects() const { return verification && !viewpoints; }
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
  MagnitudeShells magnitude; ///< of the coarse occupancy (magnitudeShells)
  double preparation_ms = 0.0;
};

namespace detail {

using Clock = std::chrono::steady_clock;

/** Milliseconds since \a start. */
inline double msSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/** Bandwidth of the magnitude shells (5.6 deg cells; the polish refines) and the
 *  peaks they add: on the bunny views the truth lay within the first ten. */
constexpr int kMagnitudeBandwidth = 32;
constexpr int kMagnitudeCandidates = 10;

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
  VerificationSamples polish;     ///< samples thinned for the polish's steps
  SurfacePatches patches;         ///< planar patches of the source (coarse voxels)
  FreeSpace free_space;           ///< what the source's sensor saw through
  Eigen::Matrix3Xd coarse_points; ///< thinned for the pass-1 (binary) occupancy grids
};

/** What pass 1 found: every hypothesis, verified, and the one chosen with its pose. */
struct GlobalSearch {
  std::vector<Hypothesis> hypotheses;
  int chosen = 0;
  Pose pose;
  /** The first choice was verified, within the limits and distinct: the later passes
   *  and the rotation refinement are skipped (they change such a pose by hundredths of
   *  a degree, if at all). */
  bool decided = false;
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

} // namespace detail
} // namespace pcl::phaser
