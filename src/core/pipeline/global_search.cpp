/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Pass 1, the global search: rotation hypotheses, their coarse translations,
 * verification and local refinement, and the choice among them.
 */
#include "pipeline/global_search.h"
#include "pipeline/pipeline_stages.h"
#include "pipeline/pipeline_verdict.h"
#include "priors/region.h"
#include "priors/tilt_prior.h"

namespace pcl::phaser {
namespace detail {
namespace {

/** Inlier share one hypothesis at least must reach for verification to rank them. */
constexpr double kMinRankingInliers = 0.1;
/** Hypotheses with at least this share of the most inliers rank above the others. */
constexpr double kMinSupport = 0.5;
/** Largest surface thickness, in verification radii, at which poses are verified. */
constexpr double kMaxThickness = 1.0 / 3.0;
/** When the choice would not be claimed: the translation peaks each rotation adds,
 *  their separation (coarse voxels) and the spare orientation peaks (on a partial view
 *  the right one ranked below ten others). */
constexpr int kExtraTranslationPeaks = 2;
constexpr int kPeakSeparation = 3;
constexpr int kSpareOrientationPeaks = 10;

/** The pose (R, t) with its verification (one thread). */
Pose verifiedPose(const SourceContext& source, const RigidPose& rigid,
                  StageTimes& times)
{
  Pose pose;
  static_cast<RigidPose&>(pose) = rigid;
  pose.verification = verifyBothWays(source, rigid.R, rigid.t, times, 1);
  return pose;
}

void record(Hypothesis& h, const Pose& pose)
{
  h.rotation = pose.R;
  h.translation = pose.t;
  h.verification = pose.verification;
}

/** Peaks of the correlation of the occupancy magnitudes, which need no common center
 *  (objects). */
void magnitudeHypotheses(const SourceContext& source, std::vector<Hypothesis>& out)
{
  const TargetModel& target = source.target;
  const int threads = source.params.num_threads;
  SpatialGridParameters grid;
  grid.voxel_size = target.coarse.grid.voxel_size;
  const MagnitudeShells shells =
      magnitudeShells(occupancySpectrum(makeSpatialGrid(source.coarse_points, grid),
                                        source.coarse_points, threads),
                      kMagnitudeBandwidth);
  const So3CorrelationGrid C = correlateShells(target.magnitude, shells, threads);
  const double norm = target.magnitude.norm * shells.norm;
  for (const So3GridIndex& peak :
       distinctPeaks(C, kMagnitudeCandidates, kHypothesisSeparation, threads)) {
    Hypothesis h;
    h.rotation = rotationFromEuler(gridEuler(peak, kMagnitudeBandwidth));
    h.rotation_score = norm > 0.0 ? C(peak) / norm : 0.0;
    h.from_orientation = true;
    out.push_back(h);
  }
}

/** The peaks of the range and orientation correlations; spare orientation ones apart.
 */
std::vector<Hypothesis> rotationHypotheses(const SourceContext& source,
                                           const So3CorrelationGrid& correlation,
                                           double source_norm, StageTimes& times,
                                           std::vector<Hypothesis>& spare)
{
  const StageParameters& params = source.params;
  const TargetModel& target = source.target;
  const auto start = Clock::now();
  std::vector<So3GridIndex> peaks;
  if (params.rotation_candidates > 1)
    peaks = distinctPeaks(correlation, params.rotation_candidates,
                          kHypothesisSeparation, params.num_threads);
  if (peaks.empty())
    peaks.push_back(correlation.argmax(params.num_threads));
  times.so3 += msSince(start);
  std::vector<Hypothesis> out;
  for (const So3GridIndex& peak : peaks) {
    Hypothesis h;
    h.rotation = rotationFromEuler(gridEuler(peak, params.bandwidth));
    h.rotation_score = correlation(peak) / (target.spherical_norm * source_norm);
    out.push_back(h);
  }
  if (params.objects()) {
    const auto begin = Clock::now();
    magnitudeHypotheses(source, out);
    times.orientation += msSince(begin);
  }
  if (target.orientation.size() == 0) // none about centroids or without candidates
    return out;
  const auto begin = Clock::now();
  const int bandwidth = params.orientation_bandwidth;
  const SphericalSpectrum O =
      orientationSpectrum(source.patches, bandwidth, params.num_threads);
  const So3CorrelationGrid Co = So3Correlator::instance(bandwidth)->correlate(
      target.orientation, O, params.num_threads, tiltPriorRows(params, bandwidth));
  const double norm =
      std::sqrt(spectrumSquaredNorm(target.orientation) * spectrumSquaredNorm(O));
  const std::vector<So3GridIndex> orientation_peaks =
      distinctPeaks(Co, params.orientation_candidates + kSpareOrientationPeaks,
                    kHypothesisSeparation, params.num_threads);
  for (std::size_t k = 0; k < orientation_peaks.size(); ++k) {
    Hypothesis h;
    h.rotation = rotationFromEuler(gridEuler(orientation_peaks[k], bandwidth));
    h.rotation_score = norm > 0.0 ? Co(orientation_peaks[k]) / norm : 0.0;
    h.from_orientation = true;
    (static_cast<int>(k) < params.orientation_candidates ? out : spare).push_back(h);
  }
  times.orientation += msSince(begin);
  return out;
}

/** By \a support of inliers, then rank (no limits: pass-1 figures are not final). */
bool ranksAbove(const Verification& a, const Verification& b, double support)
{
  const bool a_supported = a.inlier_fraction >= support;
  if (a_supported != (b.inlier_fraction >= support))
    return a_supported;
  return a.rank > b.rank;
}

/** Whether verification tells poses apart: dense enough clouds (else about centroids
 *  the peak rule decides), thin surfaces in both. */
bool canVerify(const SourceContext& source)
{
  const double limit = kMaxThickness * source.target.index.radius();
  return source.params.verification && source.patches.thickness <= limit &&
         source.target.thickness <= limit;
}

/** runTasks of \a task(k, its times); the wall time into \a times in their proportions.
 */
template <typename Task>
void runTimed(const SourceContext& source, std::size_t n, StageTimes& times,
              const Task& task)
{
  std::vector<StageTimes> task_times(n);
  const auto start = Clock::now();
  runTasks(static_cast<int>(n), source.params.num_threads, [&](int k) {
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

/** Hypotheses from \a first on translated, verified and (where possible; before it the
 *  right one often ranks low) refined. */
void translateHypotheses(const SourceContext& source,
                         std::vector<Hypothesis>& hypotheses, StageTimes& times,
                         std::size_t first = 0)
{
  const bool refined = canVerify(source);
  runTimed(source, hypotheses.size() - first, times,
           [&](std::size_t k, StageTimes& task) {
             Hypothesis& h = hypotheses[first + k];
             const SpatialCorrelationResult shift = correlateTranslation(
                 source.target.coarse, h.rotation * source.coarse_points,
                 source.params.whitening, 1, task, nullptr, nullptr, maxShift(source));
             h.overlap = shift.peak_value;
             const Pose pose = verifiedPose(source, {h.rotation, shift.shift}, task);
             record(h, refined ? refineOnSamples(source, pose, task, 1) : pose);
           });
}

/** More translation peaks per rotation: on partial views the highest can be off. */
void addTranslationPeaks(const SourceContext& source,
                         const std::vector<Eigen::Matrix3d>& rotations,
                         std::vector<Hypothesis>& hypotheses, StageTimes& times)
{
  const std::size_t n = rotations.size();
  std::vector<std::vector<Pose>> extra(n);
  const TargetModel& target = source.target;
  runTimed(source, n, times, [&](std::size_t k, StageTimes& task) {
    const auto begin = Clock::now();
    const Eigen::Matrix3d& R = rotations[k];
    // The pass-1 correlation again: cheaper than keeping every volume (16 MB each).
    SpatialVolume C = correlateSpectraWhitened(
        target.coarse,
        occupancySpectrum(target.coarse.grid, R * source.coarse_points, 1),
        source.params.whitening, 1);
    if (source.params.region)
      keepShiftsWithin(C, Eigen::Vector3d::Zero(), maxShift(source));
    std::vector<SpatialCorrelationResult> peaks =
        findDistinctSpatialPeaks(C, 1 + kExtraTranslationPeaks, kPeakSeparation);
    task.translation += msSince(begin);
    for (std::size_t j = 1; j < peaks.size(); ++j)
      extra[k].push_back(refineOnSamples(
          source, verifiedPose(source, {R, peaks[j].shift}, task), task, 1));
  });
  for (std::size_t k = 0; k < n; ++k)
    for (const Pose& pose : extra[k]) {
      Hypothesis h = hypotheses[k];
      record(h, pose);
      hypotheses.push_back(h);
    }
}

/** The best verified hypothesis if poses can be verified, else the most overlapping. */
void chooseHypothesis(const SourceContext& source, GlobalSearch& search)
{
  const std::vector<Hypothesis>& hypotheses = search.hypotheses;
  bool verifiable = false;
  double most_inliers = 0.0;
  for (const Hypothesis& h : hypotheses) {
    verifiable = verifiable || h.verification.inlier_fraction >= kMinRankingInliers;
    most_inliers = std::max(most_inliers, h.verification.inlier_fraction);
  }
  verifiable = verifiable && canVerify(source);
  std::size_t best = 0;
  for (std::size_t k = 1; k < hypotheses.size(); ++k) {
    const Hypothesis& h = hypotheses[k];
    const bool better =
        verifiable ? ranksAbove(h.verification, hypotheses[best].verification,
                                kMinSupport * most_inliers)
                   : !h.from_orientation && h.overlap > hypotheses[best].overlap;
    if (better)
      best = k;
  }
  search.chosen = static_cast<int>(best);
  search.pose = Pose();
  search.pose.R = hypotheses[best].rotation;
  search.pose.t = hypotheses[best].translation;
  search.pose.verification = hypotheses[best].verification;
  search.pose.verifiable = verifiable;
}

} // namespace

// When the choice would not be claimed (it misses the limits or does not stand out),
// the spare orientation and more translation peaks join and it is made again.
GlobalSearch globalSearch(const SourceContext& source,
                          const So3CorrelationGrid& correlation, double source_norm,
                          StageTimes& times)
{
  GlobalSearch search;
  std::vector<Hypothesis> spare;
  search.hypotheses =
      rotationHypotheses(source, correlation, source_norm, times, spare);
  std::vector<Eigen::Matrix3d> rotations;
  for (const Hypothesis& h : search.hypotheses)
    rotations.push_back(h.rotation); // before the refinement moves them
  translateHypotheses(source, search.hypotheses, times);
  chooseHypothesis(source, search);
  const auto start = Clock::now();
  const bool widen = canVerify(source) &&
                     (!meetsLimits(search.pose.verification, source.params) ||
                      !standsOut(source, search.pose, search.hypotheses).stands_out);
  times.verification += msSince(start);
  search.decided = search.pose.verifiable && !widen;
  if (widen) {
    const std::size_t first = search.hypotheses.size();
    search.hypotheses.insert(search.hypotheses.end(), spare.begin(), spare.end());
    translateHypotheses(source, search.hypotheses, times, first);
    addTranslationPeaks(source, rotations, search.hypotheses, times);
    chooseHypothesis(source, search);
  }
  return search;
}

} // namespace detail
} // namespace pcl::phaser
