/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include <pcl_phaser/core/cloud_signals.h>
#include <pcl_phaser/core/error.h>
#include <pcl_phaser/core/peak_neighbourhood.h>
#include <pcl_phaser/core/pipeline.h>
#include <pcl_phaser/core/so3_correlation.h>
#include <pcl_phaser/core/so3_refinement.h>
#include <pcl_phaser/core/spatial_correlation.h>
#include <pcl_phaser/core/spherical_harmonics.h>
#include <pcl_phaser/core/spherical_sampling.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace pcl_phaser {

namespace {

using Clock = std::chrono::steady_clock;

/** Rotation peaks closer than this are one hypothesis (a few grid cells at B = 64). */
constexpr double kHypothesisSeparation = 10.0 * M_PI / 180.0;

double msSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

SpatialGridParameters gridParameters(const PhaserParameters& p)
{
  SpatialGridParameters g;
  g.grid_size = p.spatial_grid_size;
  g.voxel_size = p.voxel_size;
  return g;
}

/** Fused spherical spectrum of a cloud; throws when the cloud carries no spherical
 *  signal. */
SphericalSpectrum sphericalSpectrum(const Eigen::Matrix3Xd& points,
                                    const ChannelValues& channels,
                                    const PhaserParameters& p, const char* which,
                                    double& sampling_ms, double& sht_ms,
                                    SphericalSupport* support = nullptr)
{
  int observed = 0;
  SphericalSpectrum F =
      cloudSphericalSpectrum(points, channels, p.bandwidth, p.fusion_levels,
                             p.num_threads, observed, sampling_ms, sht_ms, support);
  if (observed < 2)
    throw InvalidArgument(
        std::string(which) +
        " cloud has fewer than two distinct directions from its "
        "projection centre (empty, all at the centre, or a single point)");
  if (!(spectrumSquaredNorm(F) > 0.0))
    throw InvalidArgument(std::string(which) + " cloud is constant on the sphere");
  return F;
}

} // namespace

class TargetModel {
public:
  PhaserParameters params;
  std::size_t channels = 0; ///< number of fused channels beyond the geometry
  SphericalSpectrum spherical;
  SphericalSupport spherical_support; ///< for the normalised refinement
  double spherical_norm = 0.0;
  SpatialSpectrum coarse; ///< whole target, padded: any shift up to half the extent
  /** Occupancy only, when channels are fused: ranks rotation hypotheses by geometric
   *  overlap (a fused peak mixes in zero-centred channel terms, which are no overlap).
   */
  SpatialSpectrum coarse_geometry, fine_geometry;
  SpatialSpectrum fine; ///< inner region, little padding: the residual of later passes
  double coarse_energy = 0.0, fine_energy = 0.0; ///< spectrumEnergy of coarse and fine
  double preparation_ms = 0.0;
};

namespace {

/** The source's spherical spectrum, timed; with its support when \a support is given.
 */
SphericalSpectrum sourceSpectrum(const Eigen::Matrix3Xd& points,
                                 const ChannelValues& channels,
                                 const PhaserParameters& p, PhaserEstimate& e,
                                 SphericalSupport* support = nullptr)
{
  return sphericalSpectrum(points, channels, p, "source", e.sampling_ms, e.sht_ms,
                           support);
}

/** The global search: C on the SO(3) grid. */
So3CorrelationGrid correlateRotation(const TargetModel& target,
                                     const SphericalSpectrum& H,
                                     const PhaserParameters& p, PhaserEstimate& e)
{
  const auto t = Clock::now();
  So3CorrelationGrid C = So3Correlator::instance(p.bandwidth)
                             ->correlate(target.spherical, H, p.num_threads);
  e.so3_ms += msSince(t);
  return C;
}

/** Newton refinement of \a R on C, timed; with PhaserParameters::normalized_refinement
 *  then on the energy-normalised correlation (see refineRotation: plain C leans towards
 *  equal sensor tilt) near that maximum, with the supports given. Returns the exact C
 *  at the result through \a value. */
Eigen::Matrix3d refine(const TargetModel& target, const SphericalSpectrum& H,
                       const SphericalSupport& support, const Eigen::Matrix3d& R,
                       const PhaserParameters& p, double& value, PhaserEstimate& e)
{
  const auto t = Clock::now();
  RefinedRotation refined = refineRotation(target.spherical, H, R, p.bandwidth,
                                           p.refinement_iterations, p.num_threads);
  if (p.normalized_refinement)
    refined = refineRotation(target.spherical, H, refined.rotation, p.bandwidth,
                             p.refinement_iterations, p.num_threads,
                             &target.spherical_support, &support,
                             normalizedRefinementRadius(p.bandwidth));
  value = refined.value;
  e.refinement_ms += msSince(t);
  return refined.rotation;
}

/** Translation: the (already rotated) source voxelised into the grid of \a target, 3-D
 *  correlation, sub-voxel peak; the correlation volume is kept when \a volume is given.
 */
SpatialCorrelationResult
estimateShift(const SpatialSpectrum& target, const Eigen::Matrix3Xd& points,
              const ChannelValues& channels, const PhaserParameters& p,
              PhaserEstimate& e, SpatialVolume* volume = nullptr,
              bool with_score = false, double* source_energy = nullptr)
{
  const auto t = Clock::now();
  SpatialSpectrum S = cloudSpatialSpectrum(target.grid, points, channels,
                                           p.fusion_levels, p.num_threads);
  if (source_energy) // |g|^2, for the mismatch of the translation covariance
    *source_energy = spectrumEnergy(S);
  // S is not needed afterwards: the product reuses its buffer.
  SpatialVolume C = correlateSpectra(target, std::move(S), p.num_threads);
  const SpatialCorrelationResult shift =
      findSpatialPeak(C, SpatialPeakRefinement::kGaussian, p.num_threads, with_score);
  if (with_score)
    e.translation_score = shift.score;
  e.translation_ms += msSince(t);
  if (volume)
    *volume = std::move(C);
  return shift;
}

/** Correlation peak over the norms of the two grids (0 when one is empty). */
double normalizedPeak(double peak, double energy_product)
{
  return energy_product > 0.0 ? peak / std::sqrt(energy_product) : 0.0;
}

/** Grid samples around a peak as rotations of the final estimate: each sample's offset
 *  from the peak, delta_i = R_i R_peak^T, applied on the left of \a estimate (so the
 *  spread is expressed in the target frame), with weights from the correlation above
 * the lowest value of the block. */
void rotationSamples(const So3CorrelationGrid& C, const So3GridIndex& peak,
                     const Eigen::Matrix3d& estimate, PhaserEstimate& e)
{
  const std::vector<RotationSample> block = rotationNeighbourhood(C, peak, 1);
  const Eigen::Matrix3d R_peak =
      rotationFromEuler(gridEuler(peak, C.outputBandwidth()));
  double lowest = block.front().value;
  for (const RotationSample& s : block)
    lowest = std::min(lowest, s.value);
  e.rotation_samples.clear();
  e.rotation_weights.clear();
  for (const RotationSample& s : block) {
    const Eigen::Quaterniond q(s.rotation * R_peak.transpose() * estimate);
    e.rotation_samples.emplace_back(q.w(), q.x(), q.y(), q.z());
    e.rotation_weights.push_back(s.value - lowest);
  }
}

/** The target points inside the cube that holds the inner 75% of them (by distance from
 *  the centre): after the first pass the residual shift is small, so a fine grid over
 *  the densely observed region measures it best. */
std::vector<Eigen::Index> innerRegion(const Eigen::Matrix3Xd& points)
{
  std::vector<double> r(points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    r[i] = points.col(i).cwiseAbs().maxCoeff();
  std::vector<double> sorted = r;
  const std::size_t k = (sorted.size() * 3) / 4;
  std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
  const double half = sorted[k];
  std::vector<Eigen::Index> inner;
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    if (r[i] <= half)
      inner.push_back(i);
  return inner;
}

} // namespace

std::string validateParameters(const PhaserParameters& p)
{
  if (p.bandwidth < 1 || p.bandwidth > kMaxBandwidth)
    return "bandwidth must be in [1, 256], got " + std::to_string(p.bandwidth);
  if (p.voxel_size == 0.0 && (p.spatial_grid_size < 8 || p.spatial_grid_size > 1024))
    return "spatial grid size must be in [8, 1024], got " +
           std::to_string(p.spatial_grid_size);
  if (!(p.voxel_size >= 0.0) || !std::isfinite(p.voxel_size))
    return "voxel size must be >= 0 (0 = derived from the grid size), got " +
           std::to_string(p.voxel_size);
  if (p.refinement_iterations < 0 || p.refinement_iterations > 10)
    return "refinement iterations must be in [0, 10], got " +
           std::to_string(p.refinement_iterations);
  if (p.rotation_candidates < 1 || p.rotation_candidates > 10)
    return "number of rotation candidates must be in [1, 10], got " +
           std::to_string(p.rotation_candidates);
  if (p.fusion_levels < 1 || p.fusion_levels > 8)
    return "fusion levels must be in [1, 8], got " + std::to_string(p.fusion_levels);
  if (p.passes < 1 || p.passes > 5)
    return "number of passes must be in [1, 5], got " + std::to_string(p.passes);
  if (p.num_threads < 1 || p.num_threads > 64)
    return "number of threads must be in [1, 64], got " + std::to_string(p.num_threads);
  return {};
}

std::shared_ptr<const TargetModel> prepareTarget(const Eigen::Matrix3Xd& points,
                                                 const PhaserParameters& params,
                                                 const ChannelValues& raw_channels)
{
  const std::string problem = validateParameters(params);
  if (!problem.empty())
    throw InvalidArgument(problem);
  const auto start = Clock::now();
  const ChannelValues channels = normalizeChannels(raw_channels, points.cols());
  auto model = std::make_shared<TargetModel>();
  model->params = params;
  model->channels = channels.size();
  double sampling_ms = 0.0, sht_ms = 0.0;
  model->spherical = sphericalSpectrum(
      points, channels, params, "target", sampling_ms, sht_ms,
      params.normalized_refinement ? &model->spherical_support : nullptr);
  model->spherical_norm = std::sqrt(spectrumSquaredNorm(model->spherical));
  SpatialGridParameters coarse_grid;
  coarse_grid.grid_size = params.spatial_grid_size;
  const SpatialGrid coarse = makeSpatialGrid(points, coarse_grid);
  model->coarse = cloudSpatialSpectrum(coarse, points, channels, params.fusion_levels,
                                       params.num_threads);
  model->coarse_energy = spectrumEnergy(model->coarse);
  if (!channels.empty())
    model->coarse_geometry = cloudSpatialSpectrum(
        coarse, points, {}, params.fusion_levels, params.num_threads);
  if (params.passes > 1) {
    const std::vector<Eigen::Index> keep = innerRegion(points);
    Eigen::Matrix3Xd inner(3, keep.size());
    ChannelValues inner_channels(channels.size(), Eigen::VectorXd(keep.size()));
    for (std::size_t i = 0; i < keep.size(); ++i) {
      inner.col(i) = points.col(keep[i]);
      for (std::size_t c = 0; c < channels.size(); ++c)
        inner_channels[c][i] = channels[c][keep[i]];
    }
    SpatialGridParameters fine_grid = gridParameters(params);
    fine_grid.padding = 0.1;
    fine_grid.min_margin = 2.0 * fine_grid.padding * inner.cwiseAbs().maxCoeff();
    const SpatialGrid fine = makeSpatialGrid(inner, fine_grid);
    model->fine = cloudSpatialSpectrum(fine, inner, inner_channels,
                                       params.fusion_levels, params.num_threads);
    model->fine_energy = spectrumEnergy(model->fine);
    if (!channels.empty())
      model->fine_geometry = cloudSpatialSpectrum(fine, inner, {}, params.fusion_levels,
                                                  params.num_threads);
  }
  model->preparation_ms = msSince(start);
  return model;
}

double preparationTime(const TargetModel& model)
{
  return model.preparation_ms;
}

PhaserEstimate estimateTransform(const TargetModel& target,
                                 const Eigen::Matrix3Xd& points,
                                 const PhaserParameters& p,
                                 const ChannelValues& raw_channels)
{
  const std::string problem = validateParameters(p);
  if (!problem.empty())
    throw InvalidArgument(problem);
  if (target.params.bandwidth != p.bandwidth ||
      target.params.spatial_grid_size != p.spatial_grid_size ||
      target.params.voxel_size != p.voxel_size || target.params.passes != p.passes ||
      target.params.normalized_refinement != p.normalized_refinement)
    throw InvalidArgument("the target model was prepared with other parameters");
  if (p.passes > 1 && target.fine.coefficients.empty())
    throw InvalidArgument("the target model was prepared for a single pass");
  if (raw_channels.size() != target.channels)
    throw InvalidArgument("the source has " + std::to_string(raw_channels.size()) +
                          " channels, the target " + std::to_string(target.channels));
  const ChannelValues channels = normalizeChannels(raw_channels, points.cols());
  PhaserEstimate e;
  const bool single = p.passes == 1;

  // Pass 1: the global search about the source's own centre. Each of the best distinct
  // grid peaks (symmetric scenes have several) goes through the translation stage; the
  // one whose rotated source overlaps the target most wins.
  // Only the spectrum that is refined needs a support, and only for the normalised
  // refinement.
  SphericalSupport support;
  SphericalSupport* const wants_support = p.normalized_refinement ? &support : nullptr;
  SphericalSpectrum H =
      sourceSpectrum(points, channels, p, e, single ? wants_support : nullptr);
  So3CorrelationGrid C = correlateRotation(target, H, p, e);
  std::vector<So3GridIndex> peaks;
  if (p.rotation_candidates > 1)
    peaks =
        distinctPeaks(C, p.rotation_candidates, kHypothesisSeparation, p.num_threads);
  if (peaks.empty())
    peaks.push_back(C.argmax(p.num_threads));
  const double h_norm = std::sqrt(spectrumSquaredNorm(H));
  std::size_t best = 0;
  for (std::size_t k = 0; k < peaks.size(); ++k) {
    RotationHypothesis hyp;
    hyp.rotation = rotationFromEuler(gridEuler(peaks[k], p.bandwidth));
    hyp.rotation_score = C(peaks[k]) / (target.spherical_norm * h_norm);
    // Geometry alone ranks the hypotheses (see TargetModel::coarse_geometry), on the
    // coarse grid: only the winner pays for the fine one.
    const SpatialCorrelationResult shift =
        estimateShift(target.channels > 0 ? target.coarse_geometry : target.coarse,
                      hyp.rotation * points, ChannelValues{}, p, e);
    hyp.translation = shift.shift;
    hyp.overlap = shift.peak_value;
    e.hypotheses.push_back(hyp);
    if (hyp.overlap > e.hypotheses[best].overlap)
      best = k;
  }
  e.chosen_hypothesis = static_cast<int>(best);
  Eigen::Matrix3d R = e.hypotheses[best].rotation;
  Eigen::Vector3d t = e.hypotheses[best].translation;
  // Intermediate shifts only steer the viewpoint of the next pass: geometry suffices;
  // the channels are fused into the final shift.
  const ChannelValues none;
  const SpatialSpectrum& fine_geometry =
      target.channels > 0 ? target.fine_geometry : target.fine;
  if (!single) // the winner's residual shift on the fine grid
    t += estimateShift(fine_geometry, (R * points).colwise() + t, none, p, e).shift;
  So3GridIndex peak = peaks[best];
  e.passes = 1;
  double value = C(peak);
  SpatialVolume last_shift;
  if (single) {
    R = refine(target, H, support, R, p, value, e);
    double energy = 0.0;
    const SpatialCorrelationResult shift = estimateShift(
        target.coarse, R * points, channels, p, e, &last_shift, true, &energy);
    t = shift.shift;
    e.normalized_overlap =
        normalizedPeak(shift.peak_value, target.coarse_energy * energy);
    e.translation_covariance =
        translationCovariance(last_shift, shift.index, target.coarse_energy * energy);
    rotationSamples(C, peak, R, e);
    e.rotation = R;
    e.translation = t;
    e.rotation_score = value / (target.spherical_norm * h_norm);
    return e;
  }
  // Later passes: the source, moved by the estimate, is seen from the target's centre,
  // so its range function no longer suffers the parallax of the source's viewpoint; the
  // residual rotation and a fine-grid shift are composed with the estimate. A pass
  // whose shift update is below a quarter of a fine voxel started from the right
  // viewpoint, so another would not change the rotation: stop there.
  const double settled = 0.25 * target.fine.grid.voxel_size;
  for (int pass = 1; pass < p.passes; ++pass) {
    H = sourceSpectrum((R * points).colwise() + t, channels, p, e);
    C = correlateRotation(target, H, p, e);
    peak = C.argmax(p.num_threads);
    const Eigen::Matrix3d dR = rotationFromEuler(gridEuler(peak, p.bandwidth));
    R = dR * R;
    t = dR * t;
    const Eigen::Vector3d shift =
        estimateShift(fine_geometry, (R * points).colwise() + t, none, p, e).shift;
    t += shift;
    e.passes = pass + 1;
    if (shift.norm() < settled)
      break;
  }
  // Finally the residual rotation from the final viewpoint, Newton-refined from the
  // identity (it is within the grid spacing by now), and the matching shift. The spread
  // of the last grid around its peak and of the last 3-D correlation around its peak
  // describe the uncertainty.
  const SphericalSpectrum H_final =
      sourceSpectrum((R * points).colwise() + t, channels, p, e, wants_support);
  const Eigen::Matrix3d dR =
      refine(target, H_final, support, Eigen::Matrix3d::Identity(), p, value, e);
  R = dR * R;
  t = dR * t;
  double energy = 0.0;
  const SpatialCorrelationResult shift =
      estimateShift(target.fine, (R * points).colwise() + t, channels, p, e,
                    &last_shift, true, &energy);
  t += shift.shift;
  e.normalized_overlap = normalizedPeak(shift.peak_value, target.fine_energy * energy);
  e.translation_covariance =
      translationCovariance(last_shift, shift.index, target.fine_energy * energy);
  rotationSamples(C, peak, R, e);
  e.rotation_score =
      value / (target.spherical_norm * std::sqrt(spectrumSquaredNorm(H_final)));
  e.rotation = R;
  e.translation = t;
  return e;
}

} // namespace pcl_phaser
