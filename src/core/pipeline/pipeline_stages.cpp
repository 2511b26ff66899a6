/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "pipeline/pipeline_internal.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <vector>

namespace pcl::phaser {
namespace detail {

namespace {

/** Verification of the pose (R, t) with \a threads threads (default: the parameters').
 */
PoseVerification verify(const SourceContext& s, const Eigen::Matrix3d& R,
                        const Eigen::Vector3d& t, PhaserEstimate& e, int threads = 0)
{
  const auto start = Clock::now();
  if (threads <= 0)
    threads = s.p.num_threads;
  PoseVerification v = verifyPose(s.target.index, s.samples, R, t, threads,
                                  s.p.sensor_centered ? &s.target.free_space : nullptr);
  // The other way: target samples in space the source's sensor saw through.
  if (s.p.sensor_centered)
    v.reverse_free_space_violation =
        freeSpaceViolation(s.free_space, s.target.samples, s.target.sample_weights,
                           R.transpose(), -(R.transpose() * t), threads);
  e.verification_ms += msSince(start);
  return v;
}

/** Rotation hypotheses: the distinct peaks of the range correlation \a C and of the
 *  orientation histograms' correlation; the next kSpareOrientationPeaks distinct peaks
 *  of the latter into \a spare (the peaks are taken greedily, so the first ones are
 *  those a request for fewer gives). */
std::vector<RotationHypothesis>
rotationHypotheses(const SourceContext& s, const So3CorrelationGrid& C, double h_norm,
                   PhaserEstimate& e, std::vector<RotationHypothesis>& spare)
{
  const StageParameters& p = s.p;
  const auto start = Clock::now();
  std::vector<So3GridIndex> peaks;
  if (p.rotation_candidates > 1)
    peaks =
        distinctPeaks(C, p.rotation_candidates, kHypothesisSeparation, p.num_threads);
  if (peaks.empty())
    peaks.push_back(C.argmax(p.num_threads));
  e.so3_ms += msSince(start); // the peaks are part of the rotation search
  std::vector<RotationHypothesis> out;
  for (const So3GridIndex& peak : peaks) {
    RotationHypothesis h;
    h.rotation = rotationFromEuler(gridEuler(peak, p.bandwidth));
    h.rotation_score = C(peak) / (s.target.spherical_norm * h_norm);
    out.push_back(h);
  }
  if (!p.sensor_centered || p.orientation_candidates == 0 ||
      s.target.orientation.size() == 0)
    return out;
  const auto t = Clock::now();
  const SphericalSpectrum O =
      orientationSpectrum(s.patches, p.orientation_bandwidth, p.num_threads);
  const So3CorrelationGrid Co = So3Correlator::instance(p.orientation_bandwidth)
                                    ->correlate(s.target.orientation, O, p.num_threads);
  const double norm =
      std::sqrt(spectrumSquaredNorm(s.target.orientation) * spectrumSquaredNorm(O));
  const std::vector<So3GridIndex> orientation_peaks =
      distinctPeaks(Co, p.orientation_candidates + kSpareOrientationPeaks,
                    kHypothesisSeparation, p.num_threads);
  for (std::size_t k = 0; k < orientation_peaks.size(); ++k) {
    const So3GridIndex& peak = orientation_peaks[k];
    RotationHypothesis h;
    h.rotation = rotationFromEuler(gridEuler(peak, p.orientation_bandwidth));
    h.rotation_score = norm > 0.0 ? Co(peak) / norm : 0.0;
    h.from_orientation = true;
    (static_cast<int>(k) < p.orientation_candidates ? out : spare).push_back(h);
  }
  e.orientation_ms += msSince(t);
  return out;
}

/** Whether verification \a a ranks above \a b: one with at least \a support of
 *  inliers above one without (a pose that matches far less than another has little
 *  support, however little it violates: noise puts the right pose's samples in space
 * the target saw through, and a pose whose samples land where the target saw nothing
 *  violates least), then by rank() (a wrong pose can match more samples than the right
 *  one, e.g. a 180 deg flip of a symmetric yard, and still see through the target's
 *  surfaces). The verification limits take no part: they judge the final pose, while a
 *  pass-1 pose is a voxel and a grid cell off, its constraint and free-space shares not
 *  yet those of the refined pose (benchmarks.md 9.18). */
bool ranksAbove(const PoseVerification& a, const PoseVerification& b, double support)
{
  const bool a_supported = a.inlier_fraction >= support;
  const bool b_supported = b.inlier_fraction >= support;
  if (a_supported != b_supported)
    return a_supported;
  return rank(a) > rank(b);
}

/** Whether a refined pose replaces the current one: when the poses are ranked by
 *  verification, if it ranks no worse; otherwise always (the passes' own stop rule
 *  decides). */
bool accept(const Pose& next, const Pose& current)
{
  return !current.verifiable || rank(next.v) > rank(current.v);
}

/** Whether verification can tell poses apart: about sensor origins, with surfaces
 *  thinner than a third of the verification radius in both clouds (noise thicker than
 *  that lets wrong poses put as many samples within the radius as the right one). */
bool canVerify(const SourceContext& s)
{
  const double limit = kMaxThickness * s.target.index.radius();
  return s.p.sensor_centered && s.patches.thickness <= limit &&
         s.target.thickness <= limit;
}

/** \a pose refined by refinePoseWithin (within the hypothesis separation and two
 *  coarse voxels; its first step against the target's reach index), kept when it
 *  verifies better. */
Pose polish(const SourceContext& s, const Pose& pose, PhaserEstimate& e,
            int num_threads)
{
  const auto start = Clock::now();
  const RigidPose refined =
      refinePoseWithin(s.target.index, s.samples, {pose.R, pose.t}, kPolishIterations,
                       kHypothesisSeparation, 2.0 * s.target.coarse.grid.voxel_size,
                       &s.target.reach_index);
  e.verification_ms += msSince(start);
  if (refined.R == pose.R && refined.t == pose.t)
    return pose; // refused or nothing to climb: verifies as before
  Pose next = pose;
  next.R = refined.R;
  next.t = refined.t;
  next.v = verify(s, next.R, next.t, e, num_threads);
  return rank(next.v) > rank(pose.v) ? next : pose;
}

/** The residual rotation's correlation grid from the current viewpoint: only rotations
 *  that tilt less than kResidualTilt (any yaw). */
std::shared_ptr<So3CorrelationGrid>
residualGrid(const SourceContext& s, const SphericalSpectrum& H, PhaserEstimate& e)
{
  const auto start = Clock::now();
  const int rows = betaRowsForTilt(s.p.bandwidth, kResidualTilt);
  auto C = std::make_shared<So3CorrelationGrid>(
      So3Correlator::instance(s.p.bandwidth)
          ->correlate(s.target.spherical, H, s.p.num_threads, rows));
  e.so3_ms += msSince(start);
  return C;
}

/** Adds the wall time \a wall of a region of tasks to e's translation and verification
 *  times, split in the proportions of the tasks' own times. */
void splitWallTime(const std::vector<PhaserEstimate>& times, double wall,
                   PhaserEstimate& e)
{
  double translation = 0.0, verification = 0.0;
  for (const PhaserEstimate& t : times) {
    translation += t.translation_ms;
    verification += t.verification_ms;
  }
  const double busy = translation + verification;
  e.translation_ms += busy > 0.0 ? wall * translation / busy : 0.0;
  e.verification_ms += busy > 0.0 ? wall * verification / busy : 0.0;
}

/** Every hypothesis from index \a first on through the coarse translation search and
 *  verification, then (where poses can be verified) the polish, into e.hypotheses and
 *  \a v (resized to hold them): before the polish the right hypothesis often ranks low
 *  (a voxel and a grid cell off, its samples fall in free space), so every one is
 *  polished. Each hypothesis is a one-thread task (runTasks), so its result does not
 *  depend on the thread count. The stage times are the wall time of the regions, split
 *  in the tasks' proportions. */
void translateHypotheses(const SourceContext& s, PhaserEstimate& e,
                         std::vector<PoseVerification>& v, std::size_t first = 0)
{
  const std::size_t n = e.hypotheses.size() - first;
  PhaserParameters single = s.p;
  single.num_threads = 1;
  std::vector<PhaserEstimate> times(n);
  std::vector<Pose> poses(n);
  const bool polished = canVerify(s);
  const auto start = Clock::now();
  runTasks(static_cast<int>(n), s.p.num_threads, [&](int k) {
    RotationHypothesis& h = e.hypotheses[first + static_cast<std::size_t>(k)];
    Pose& pose = poses[static_cast<std::size_t>(k)];
    const SpatialCorrelationResult shift = shiftOf(
        s.target.coarse, h.rotation * s.coarse_points, s.p.whitening, single, times[k]);
    h.overlap = shift.peak_value;
    pose.R = h.rotation;
    pose.t = shift.shift;
    pose.v = verify(s, pose.R, pose.t, times[k], 1);
    if (polished)
      pose = polish(s, pose, times[k], 1);
  });
  v.resize(first + n);
  for (std::size_t k = 0; k < n; ++k) {
    e.hypotheses[first + k].rotation = poses[k].R;
    e.hypotheses[first + k].translation = poses[k].t;
    v[first + k] = poses[k].v;
  }
  splitWallTime(times, msSince(start), e);
}

/** When the pass-1 choice would not be claimed (globalSearch): the next
 * kExtraTranslationPeaks distinct peaks (kPeakSeparation coarse voxels apart) of every
 * hypothesis's coarse translation correlation, at its grid rotation in \a rotations,
 * each a hypothesis of its own, verified and polished as in pass 1 and appended to
 * e.hypotheses and \a v. On partial views a rotation near the truth can have its
 * highest translation peak meters off (benchmarks.md 9.10). */
void widenHypotheses(const SourceContext& s,
                     const std::vector<Eigen::Matrix3d>& rotations, PhaserEstimate& e,
                     std::vector<PoseVerification>& v)
{
  const std::size_t n = rotations.size();
  std::vector<PhaserEstimate> times(n);
  std::vector<std::vector<Pose>> extra(n);
  const auto start = Clock::now();
  runTasks(static_cast<int>(n), s.p.num_threads, [&](int k) {
    const auto begin = Clock::now();
    const Eigen::Matrix3d& R = rotations[static_cast<std::size_t>(k)];
    PhaserEstimate& time = times[static_cast<std::size_t>(k)];
    // The pass-1 correlation again: keeping every pass-1 volume (16 MB each) for the
    // few aligns that widen would cost more than recomputing it there.
    const SpatialVolume C = correlateSpectraWhitened(
        s.target.coarse,
        occupancySpectrum(s.target.coarse.grid, R * s.coarse_points, 1), s.p.whitening,
        1);
    std::vector<SpatialCorrelationResult> peaks =
        findDistinctSpatialPeaks(C, 1 + kExtraTranslationPeaks, kPeakSeparation);
    time.translation_ms += msSince(begin);
    for (std::size_t j = 1; j < peaks.size(); ++j) {
      Pose pose;
      pose.R = R;
      pose.t = peaks[j].shift;
      pose.v = verify(s, pose.R, pose.t, time, 1);
      extra[static_cast<std::size_t>(k)].push_back(polish(s, pose, time, 1));
    }
  });
  for (std::size_t k = 0; k < n; ++k)
    for (const Pose& pose : extra[k]) {
      RotationHypothesis h = e.hypotheses[k];
      h.rotation = pose.R;
      h.translation = pose.t;
      e.hypotheses.push_back(h);
      v.push_back(pose.v);
    }
  splitWallTime(times, msSince(start), e);
}

/** The hypotheses' verification figures from \a v, and the pass-1 pose: about sensor
 *  origins, when at least one hypothesis puts kMinRankingInliers of the samples on the
 *  target, the best verified one; otherwise the range peak whose rotated source
 *  overlaps the target most. */
Pose choose(const SourceContext& s, const std::vector<PoseVerification>& v,
            PhaserEstimate& e)
{
  bool verifiable = false;
  double most_inliers = 0.0;
  for (std::size_t k = 0; k < e.hypotheses.size(); ++k) {
    RotationHypothesis& h = e.hypotheses[k];
    h.inlier_fraction = v[k].inlier_fraction;
    h.verification_score = v[k].score;
    h.verification_rank = rank(v[k]);
    h.free_space_violation = v[k].free_space_violation;
    h.reverse_free_space_violation = v[k].reverse_free_space_violation;
    verifiable = verifiable || v[k].inlier_fraction >= kMinRankingInliers;
    most_inliers = std::max(most_inliers, v[k].inlier_fraction);
  }
  verifiable = verifiable && canVerify(s);
  std::size_t best = 0;
  for (std::size_t k = 1; k < e.hypotheses.size(); ++k) {
    const RotationHypothesis& h = e.hypotheses[k];
    const bool better =
        verifiable ? ranksAbove(v[k], v[best], kMinSupport * most_inliers)
                   : !h.from_orientation && h.overlap > e.hypotheses[best].overlap;
    if (better)
      best = k;
  }
  e.chosen_hypothesis = static_cast<int>(best);
  Pose pose;
  pose.R = e.hypotheses[best].rotation;
  pose.t = e.hypotheses[best].translation;
  pose.v = v[best];
  pose.verifiable = verifiable;
  return pose;
}

} // namespace

/** Pass 1: every hypothesis through the coarse translation search and verification,
 *  then choose(). Where poses can be verified and the chosen one would not be claimed
 *  (it misses the limits, or a distinct hypothesis ranks about as high: standsOut), the
 *  spare orientation peaks become hypotheses too, then widenHypotheses, and choose()
 *  again. Otherwise (object scans, or clouds so noisy or sparse that no pose verifies,
 *  e.g. 1 m of noise at 40 dB PSNR) verification cannot rank them and the range peak
 *  that overlaps most wins, as the orientation histograms are as unreliable as the
 *  normals. */
Pose globalSearch(const SourceContext& s, const So3CorrelationGrid& C, double h_norm,
                  PhaserEstimate& e)
{
  std::vector<RotationHypothesis> spare;
  e.hypotheses = rotationHypotheses(s, C, h_norm, e, spare);
  std::vector<Eigen::Matrix3d> rotations;
  for (const RotationHypothesis& h : e.hypotheses)
    rotations.push_back(h.rotation); // before the polish moves them
  std::vector<PoseVerification> v;
  translateHypotheses(s, e, v);
  Pose pose = choose(s, v, e);
  const auto start = Clock::now();
  const bool widen = canVerify(s) && (!meetsLimits(pose.v, s.p) ||
                                      !standsOut(s, pose, e.hypotheses).stands_out);
  e.verification_ms += msSince(start);
  if (widen) {
    const std::size_t first = e.hypotheses.size();
    e.hypotheses.insert(e.hypotheses.end(), spare.begin(), spare.end());
    translateHypotheses(s, e, v, first);
    widenHypotheses(s, rotations, e, v);
    pose = choose(s, v, e);
  }
  e.passes = 1;
  return pose;
}

/** Later passes: the source, moved by the estimate, is seen from the target's center,
 *  so its range function no longer suffers the parallax of the source's viewpoint; the
 *  residual rotation (grid argmax among the rotations that tilt less than
 *  kResidualTilt) and a fine-grid shift are composed with the
 *  estimate, kept only while verification does not get worse. A pass whose shift
 *  update is below a quarter of a fine voxel started from the right viewpoint: stop. */
Pose reprojectionPasses(const SourceContext& s, Pose pose, PhaserEstimate& e)
{
  const double settled = 0.25 * s.target.fine.grid.voxel_size;
  for (int pass = 1; pass < s.p.passes; ++pass) {
    // With the support the final stage needs: a refused pass hands it over.
    auto view = std::make_shared<Viewpoint>();
    view->H = sourceSpectrum((pose.R * s.points).colwise() + pose.t, s.channels, s.p, e,
                             s.p.normalized_refinement ? &view->support : nullptr);
    const std::shared_ptr<So3CorrelationGrid> C = residualGrid(s, view->H, e);
    Pose next;
    next.verifiable = pose.verifiable;
    next.peak = pose.verifiable ? C->argmaxNearIdentity(kHypothesisSeparation)
                                : C->argmax(s.p.num_threads);
    next.grid = C;
    const Eigen::Matrix3d dR = rotationFromEuler(gridEuler(next.peak, s.p.bandwidth));
    next.R = dR * pose.R;
    next.t = dR * pose.t;
    const Eigen::Vector3d shift =
        shiftOf(s.target.fine, (next.R * s.points).colwise() + next.t, 0.0, s.p, e)
            .shift;
    next.t += shift;
    next.v = verify(s, next.R, next.t, e);
    if (!accept(next, pose)) {
      view->grid = C;
      view->peak = next.peak;
      pose.view = std::move(view);
      break;
    }
    pose = next;
    e.passes = pass + 1;
    if (shift.norm() < settled)
      break;
  }
  return pose;
}

/** Finally the residual rotation from the final viewpoint, Newton-refined from the
 *  identity, and the matching shift, kept when verification does not get worse. The
 *  spread of the last rotation grid around its peak and of the last 3-D correlation
 *  around its peak describe the uncertainty. */
void finalStage(const SourceContext& s, Pose pose, PhaserEstimate& e)
{
  const TargetModel& target = s.target;
  const StageParameters& p = s.p;
  // The source from this viewpoint, as a refused pass measured it, or measured now.
  std::shared_ptr<const Viewpoint> view = pose.view;
  if (!view) {
    auto measured = std::make_shared<Viewpoint>();
    measured->H =
        sourceSpectrum((pose.R * s.points).colwise() + pose.t, s.channels, p, e,
                       p.normalized_refinement ? &measured->support : nullptr);
    view = std::move(measured);
  }
  const SphericalSpectrum& H = view->H;
  const SphericalSupport& support = view->support;
  // After an accepted pass the residual is within the grid spacing: refine from the
  // identity; else search the residual grid (tilt below kResidualTilt) first.
  Eigen::Matrix3d start = Eigen::Matrix3d::Identity();
  if (!pose.grid) {
    if (view->grid) {
      pose.grid = view->grid;
      pose.peak = view->peak;
    } else {
      pose.grid = residualGrid(s, H, e);
      // A polished pose is within a grid cell or two: its peak is the one near it.
      pose.peak = pose.verifiable ? pose.grid->argmaxNearIdentity(kHypothesisSeparation)
                                  : pose.grid->argmax(p.num_threads);
    }
    start = rotationFromEuler(gridEuler(pose.peak, p.bandwidth));
  }
  // Held here: pose (and its grid) may be replaced below.
  const std::shared_ptr<const So3CorrelationGrid> rotation_grid = pose.grid;
  const So3CorrelationGrid& C = *rotation_grid;
  const So3GridIndex peak = pose.peak;
  double value = 0.0;
  const Eigen::Matrix3d dR = refine(target, H, support, start, p, value, e);
  const bool single = p.passes == 1;
  const SpatialSpectrum& grid = single ? target.coarse : target.fine;
  const double grid_energy = single ? target.coarse_energy : target.fine_energy;
  Pose next;
  next.verifiable = pose.verifiable;
  next.R = dR * pose.R;
  next.t = dR * pose.t;
  SpatialVolume volume;
  double energy = 0.0;
  const SpatialCorrelationResult shift =
      shiftOf(grid, (next.R * s.points).colwise() + next.t, single ? p.whitening : 0.0,
              p, e, &volume, &energy);
  // A wrong pose can move the source out of the fine grid: then nothing was measured.
  const bool measured = energy > 0.0;
  if (measured) {
    next.t += shift.shift;
    next.v = verify(s, next.R, next.t, e);
    e.translation_score = shift.score;
    e.normalized_overlap =
        normalizedPeak(volume.values.empty() ? 0.0 : volumeAt(volume, shift.index),
                       grid_energy * energy);
    e.translation_covariance =
        translationCovariance(volume, shift.index, grid_energy * energy);
  }
  e.rotation_score =
      value / (target.spherical_norm * std::sqrt(spectrumSquaredNorm(H)));
  if (measured && accept(next, pose))
    pose = next;
  if (pose.verifiable)
    pose = polish(s, pose, e, p.num_threads);
  rotationSamples(C, peak, pose.R, e);
  verdict(s, pose, e);
}

} // namespace detail
} // namespace pcl::phaser
