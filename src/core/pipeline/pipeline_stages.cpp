/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "pipeline/pipeline_internal.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace pcl::phaser {
namespace detail {

namespace {

/** Verification of the pose (R, t) with \a threads threads (default: the parameters'),
 *  the reverse free-space test included about sensor origins. */
Verification verifyBothWays(const SourceContext& source, const Eigen::Matrix3d& R,
                            const Eigen::Vector3d& t, StageTimes& times,
                            int threads = 0)
{
  const auto start = Clock::now();
  const StageParameters& params = source.params;
  if (threads <= 0)
    threads = params.num_threads;
  const TargetModel& target = source.target;
  PoseVerification verification =
      verifyPose(target.index, source.samples, R, t, threads,
                 params.sensor_centered ? &target.free_space : nullptr);
  if (params.sensor_centered)
    verification.reverse_free_space_violation =
        freeSpaceViolation(source.free_space, target.samples, target.sample_weights,
                           R.transpose(), -(R.transpose() * t), threads);
  times.verification += msSince(start);
  return ranked(verification);
}

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

/** Translation of the (rotated) \a points onto \a target: the occupancy correlation,
 *  whitened by \a whitening, at the sub-voxel peak. With \a volume the plain
 *  correlation is kept for the covariance and the peak's sidelobe score computed. */
SpatialCorrelationResult
correlateTranslation(const SpatialSpectrum& target, const Eigen::Matrix3Xd& points,
                     double whitening, int num_threads, StageTimes& times,
                     SpatialVolume* volume = nullptr, double* source_energy = nullptr)
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
  const SpatialCorrelationResult shift = findSpatialPeak(
      C, SpatialPeakRefinement::kGaussian, num_threads, volume != nullptr);
  if (volume)
    *volume = whitening > 0.0 ? std::move(plain) : std::move(C);
  times.translation += msSince(start);
  return shift;
}

/** Rotation hypotheses: the distinct peaks of the range correlation and of the
 *  orientation histograms' correlation; the next kSpareOrientationPeaks distinct peaks
 *  of the latter into \a spare. */
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
  if (!params.sensor_centered || params.orientation_candidates == 0 ||
      target.orientation.size() == 0)
    return out;
  const auto begin = Clock::now();
  const int bandwidth = params.orientation_bandwidth;
  const SphericalSpectrum O =
      orientationSpectrum(source.patches, bandwidth, params.num_threads);
  const So3CorrelationGrid Co = So3Correlator::instance(bandwidth)->correlate(
      target.orientation, O, params.num_threads);
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

/** Whether \a a ranks above \a b: one with at least \a support of inliers above one
 *  without (however little that one violates), then by rank. The limits take no part:
 *  a pass-1 pose is a voxel and a grid cell off, its figures not yet final. */
bool ranksAbove(const Verification& a, const Verification& b, double support)
{
  const bool a_supported = a.inlier_fraction >= support;
  const bool b_supported = b.inlier_fraction >= support;
  if (a_supported != b_supported)
    return a_supported;
  return a.rank > b.rank;
}

/** Whether \a next replaces \a current: when poses are ranked by verification, if it
 *  ranks higher; otherwise always (the passes' own stop rule decides). */
bool improves(const Pose& next, const Pose& current)
{
  return !current.verifiable || next.verification.rank > current.verification.rank;
}

/** Whether verification can tell poses apart: about sensor origins, with surfaces
 *  thinner than kMaxThickness verification radii in both clouds. */
bool canVerify(const SourceContext& source)
{
  const double limit = kMaxThickness * source.target.index.radius();
  return source.params.sensor_centered && source.patches.thickness <= limit &&
         source.target.thickness <= limit;
}

/** \a pose refined on the verification samples (refinePoseWithin: within the
 *  hypothesis separation and two coarse voxels, its first step against the target's
 *  reach index), kept when it ranks higher. */
Pose refineOnSamples(const SourceContext& source, const Pose& pose, StageTimes& times,
                     int num_threads)
{
  const auto start = Clock::now();
  const TargetModel& target = source.target;
  const RigidPose refined = refinePoseWithin(
      target.index, source.samples, pose, kLocalRefinementSteps, kHypothesisSeparation,
      2.0 * target.coarse.grid.voxel_size, &target.reach_index);
  times.verification += msSince(start);
  if (refined.R == pose.R && refined.t == pose.t)
    return pose; // refused or nothing to climb: verifies as before
  Pose next = pose;
  static_cast<RigidPose&>(next) = refined;
  next.verification = verifyBothWays(source, next.R, next.t, times, num_threads);
  return next.verification.rank > pose.verification.rank ? next : pose;
}

/** The residual rotation's correlation grid from the viewpoint of spectrum \a H: only
 *  rotations that tilt less than kResidualTilt (any yaw). */
std::shared_ptr<So3CorrelationGrid>
residualGrid(const SourceContext& source, const SphericalSpectrum& H, StageTimes& times)
{
  const auto start = Clock::now();
  const StageParameters& params = source.params;
  const int rows = betaRowsForTilt(params.bandwidth, kResidualTilt);
  auto C = std::make_shared<So3CorrelationGrid>(
      So3Correlator::instance(params.bandwidth)
          ->correlate(source.target.spherical, H, params.num_threads, rows));
  times.so3 += msSince(start);
  return C;
}

/** Adds the wall time \a wall of a region of tasks to the translation and verification
 *  times, split in the proportions of the tasks' own times. */
void splitWallTime(const std::vector<StageTimes>& task_times, double wall,
                   StageTimes& times)
{
  double translation = 0.0, verification = 0.0;
  for (const StageTimes& task : task_times) {
    translation += task.translation;
    verification += task.verification;
  }
  const double busy = translation + verification;
  times.translation += busy > 0.0 ? wall * translation / busy : 0.0;
  times.verification += busy > 0.0 ? wall * verification / busy : 0.0;
}

/** Every hypothesis from index \a first on through the coarse translation search,
 *  verification and (where poses can be verified) the local refinement: before it the
 *  right one often ranks low. One-thread tasks: results independent of thread count. */
void translateHypotheses(const SourceContext& source,
                         std::vector<Hypothesis>& hypotheses, StageTimes& times,
                         std::size_t first = 0)
{
  const std::size_t n = hypotheses.size() - first;
  std::vector<StageTimes> task_times(n);
  const bool refined = canVerify(source);
  const auto start = Clock::now();
  runTasks(static_cast<int>(n), source.params.num_threads, [&](int k) {
    Hypothesis& h = hypotheses[first + static_cast<std::size_t>(k)];
    StageTimes& task = task_times[static_cast<std::size_t>(k)];
    const SpatialCorrelationResult shift =
        correlateTranslation(source.target.coarse, h.rotation * source.coarse_points,
                             source.params.whitening, 1, task);
    h.overlap = shift.peak_value;
    const Pose pose = verifiedPose(source, {h.rotation, shift.shift}, task);
    record(h, refined ? refineOnSamples(source, pose, task, 1) : pose);
  });
  splitWallTime(task_times, msSince(start), times);
}

/** The next kExtraTranslationPeaks distinct peaks of the coarse translation
 *  correlation at each of the grid \a rotations as hypotheses, verified and refined as
 *  in pass 1: on partial views the right rotation's highest peak can be meters off. */
void addTranslationPeaks(const SourceContext& source,
                         const std::vector<Eigen::Matrix3d>& rotations,
                         std::vector<Hypothesis>& hypotheses, StageTimes& times)
{
  const std::size_t n = rotations.size();
  std::vector<StageTimes> task_times(n);
  std::vector<std::vector<Pose>> extra(n);
  const auto start = Clock::now();
  const TargetModel& target = source.target;
  runTasks(static_cast<int>(n), source.params.num_threads, [&](int k) {
    const auto begin = Clock::now();
    const Eigen::Matrix3d& R = rotations[static_cast<std::size_t>(k)];
    StageTimes& task = task_times[static_cast<std::size_t>(k)];
    // The pass-1 correlation again: cheaper than keeping every volume (16 MB each).
    const SpatialVolume C = correlateSpectraWhitened(
        target.coarse,
        occupancySpectrum(target.coarse.grid, R * source.coarse_points, 1),
        source.params.whitening, 1);
    std::vector<SpatialCorrelationResult> peaks =
        findDistinctSpatialPeaks(C, 1 + kExtraTranslationPeaks, kPeakSeparation);
    task.translation += msSince(begin);
    for (std::size_t j = 1; j < peaks.size(); ++j)
      extra[static_cast<std::size_t>(k)].push_back(refineOnSamples(
          source, verifiedPose(source, {R, peaks[j].shift}, task), task, 1));
  });
  for (std::size_t k = 0; k < n; ++k)
    for (const Pose& pose : extra[k]) {
      Hypothesis h = hypotheses[k];
      record(h, pose);
      hypotheses.push_back(h);
    }
  splitWallTime(task_times, msSince(start), times);
}

/** The pass-1 pose: about sensor origins, when at least one hypothesis puts
 *  kMinRankingInliers of the samples on the target, the best verified one; otherwise
 *  the range peak whose rotated source overlaps the target most. */
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

/** Newton refinement of \a R on C, then with normalized_refinement on the
 *  energy-normalized correlation near that maximum (plain C leans towards equal sensor
 *  tilt); the exact C at the result into \a value. */
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

/** Grid samples around \a peak of \a C, their offsets from it applied on the left of
 *  \a estimate, weighted by their correlation above the lowest of the block. */
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

/** The source seen from \a pose: its spectrum, with its support when the normalized
 *  refinement needs it. */
std::shared_ptr<Viewpoint> viewFrom(const SourceContext& source, const RigidPose& pose,
                                    StageTimes& times)
{
  auto view = std::make_shared<Viewpoint>();
  view->H = sourceSpectrum(
      (pose.R * source.points).colwise() + pose.t, source.channels, source.params,
      times, source.params.normalized_refinement ? &view->support : nullptr);
  return view;
}

/** The source seen from \a pose: as a refused pass measured it, or measured now; with
 *  the residual grid and its peak in \a pose when no accepted pass left them. */
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
    pose.grid = residualGrid(source, view->H, times);
    // A refined pose is within a grid cell or two: its peak is the one near it.
    pose.peak = pose.verifiable ? pose.grid->argmaxNearIdentity(kHypothesisSeparation)
                                : pose.grid->argmax(source.params.num_threads);
  }
  return view;
}

/** The shift of \a next on the final grid (coarse after one pass, else fine) into
 *  \a next, with its verification, and the translation figures into \a result;
 *  false when a wrong pose moved the source out of the grid (nothing measured). */
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
  next.verification = verifyBothWays(source, next.R, next.t, times);
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

/** Where poses can be verified and the chosen one would not be claimed (it misses the
 *  limits, or a distinct hypothesis ranks about as high), the spare orientation peaks
 *  and more translation peaks become hypotheses too, and the choice is made again. */
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
  if (widen) {
    const std::size_t first = search.hypotheses.size();
    search.hypotheses.insert(search.hypotheses.end(), spare.begin(), spare.end());
    translateHypotheses(source, search.hypotheses, times, first);
    addTranslationPeaks(source, rotations, search.hypotheses, times);
    chooseHypothesis(source, search);
  }
  return search;
}

/** Each pass sees the source, moved by the estimate, from the target's center (free of
 *  its own viewpoint's parallax) and composes the residual rotation (tilt below
 *  kResidualTilt) and a fine-grid shift with the estimate. A shift below a quarter of
 *  a fine voxel means the pass started from the right viewpoint: stop. */
Pose reprojectionPasses(const SourceContext& source, Pose pose, int& passes,
                        StageTimes& times)
{
  const StageParameters& params = source.params;
  const double settled = 0.25 * source.target.fine.grid.voxel_size;
  for (int pass = 1; pass < params.passes; ++pass) {
    // With the support the final refinement needs: a refused pass hands it over.
    std::shared_ptr<Viewpoint> view = viewFrom(source, pose, times);
    const std::shared_ptr<So3CorrelationGrid> C = residualGrid(source, view->H, times);
    Pose next;
    next.verifiable = pose.verifiable;
    next.peak = pose.verifiable ? C->argmaxNearIdentity(kHypothesisSeparation)
                                : C->argmax(params.num_threads);
    next.grid = C;
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
    next.verification = verifyBothWays(source, next.R, next.t, times);
    if (!improves(next, pose)) {
      view->grid = C;
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

/** The residual rotation from the final viewpoint is Newton-refined from the identity
 *  after an accepted pass, else from the residual grid's peak. */
Pose refineFinalPose(const SourceContext& source, Pose pose, PhaserResult& result)
{
  const StageParameters& params = source.params;
  StageTimes& times = result.diagnostics.times;
  const bool after_pass = pose.grid != nullptr;
  const std::shared_ptr<const Viewpoint> view = finalViewpoint(source, pose, times);
  const Eigen::Matrix3d start =
      after_pass ? Eigen::Matrix3d::Identity()
                 : rotationFromEuler(gridEuler(pose.peak, params.bandwidth));
  // Held here: pose (and its grid) may be replaced below.
  const std::shared_ptr<const So3CorrelationGrid> rotation_grid = pose.grid;
  const So3GridIndex peak = pose.peak;
  double value = 0.0;
  const Eigen::Matrix3d dR = refineResidualRotation(source, *view, start, value, times);
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
    pose = refineOnSamples(source, pose, times, params.num_threads);
  rotationSamples(*rotation_grid, peak, pose.R, result.diagnostics);
  return pose;
}

} // namespace detail
} // namespace pcl::phaser
