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
#include <pcl_phaser/core/surface_orientation.h>
#include <pcl_phaser/core/verification.h>

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
  SphericalSpectrum orientation; ///< surface-orientation histogram (may be empty)
  /** Binary occupancy on the whole target, padded (any shift up to half the extent),
   *  and on its inner region with little padding (the residual of later passes). */
  SpatialSpectrum coarse, fine;
  double coarse_energy = 0.0, fine_energy = 0.0; ///< spectrumEnergy of coarse and fine
  PointIndex index;                              ///< target points, for verifyPose
  double thickness = 0.0; ///< SurfacePatches::thickness of the target
  FreeSpace free_space; ///< what the target's sensor saw through (sensor-centred only)
  /** Evenly spaced target points with their orientation weights: the reverse
   *  free-space test, against what the source's sensor saw (sensor-centred only). */
  Eigen::Matrix3Xd samples;
  Eigen::VectorXd sample_weights;
  double preparation_ms = 0.0;
};

namespace {

/** Verification radius, in coarse voxels. */
constexpr double kVerificationVoxels = 0.5;
/** Direction cells of the free-space test (about 1.4 deg) and its margin in coarse
 *  voxels. */
constexpr int kFreeSpaceBandwidth = 128;
constexpr double kFreeSpaceMargin = 1.0;
/** Inlier share one hypothesis at least must reach for verification to rank them. */
constexpr double kMinRankingInliers = 0.1;
/** Largest surface thickness, in verification radii, at which poses are verified. */
constexpr double kMaxThickness = 1.0 / 3.0;
/** Weight of a free-space violation against an inlier in rank(). */
constexpr double kViolationWeight = 3.0;

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

/** Saturation of the occupancy grids: a voxel with a fraction of a point's weight is
 *  already almost full, so occupancy is binary and the near-sensor density (each scan
 *  is densest around its own sensor) does not vote for stacking the sensors. */
constexpr double kOccupancySaturation = 0.05;

/** Patches of the orientation histogram, in coarse voxels. */
constexpr double kPatchVoxels = 1.0;

/** Binary occupancy spectrum of \a points on \a grid. */
SpatialSpectrum occupancySpectrum(const SpatialGrid& grid,
                                  const Eigen::Matrix3Xd& points, int num_threads)
{
  SpatialVoxelParameters voxel;
  voxel.saturation = kOccupancySaturation;
  voxel.num_threads = num_threads;
  return computeSpectrum(voxelize(grid, points, voxel), num_threads);
}

/** A pose and how well it verifies; with the rotation grid of the last accepted
 *  re-projection pass (its peak is near the identity), if one was accepted. */
struct Pose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  PoseVerification v;
  std::shared_ptr<const So3CorrelationGrid> grid;
  So3GridIndex peak{};
  bool verifiable = false; ///< hypotheses and passes are ranked by verification
};

double volumeAt(const SpatialVolume& v, const Eigen::Vector3i& i)
{
  return v.values[v.grid.flatIndex(i.x(), i.y(), i.z())];
}

/** Translation of the (already rotated) \a points onto \a target by the occupancy
 *  correlation, whitened by \a whitening (correlateSpectraWhitened), sub-voxel peak.
 *  When \a volume is given (the final stage), the plain correlation volume is kept for
 *  the covariance and the peak's sidelobe score is computed. */
SpatialCorrelationResult shiftOf(const SpatialSpectrum& target,
                                 const Eigen::Matrix3Xd& points, double whitening,
                                 const PhaserParameters& p, PhaserEstimate& e,
                                 SpatialVolume* volume = nullptr,
                                 double* source_energy = nullptr)
{
  const auto t = Clock::now();
  SpatialSpectrum S = occupancySpectrum(target.grid, points, p.num_threads);
  if (source_energy)
    *source_energy = spectrumEnergy(S);
  SpatialVolume plain;
  if (volume && whitening > 0.0)
    plain = correlateSpectra(target, S, p.num_threads);
  SpatialVolume C =
      correlateSpectraWhitened(target, std::move(S), whitening, p.num_threads);
  const SpatialCorrelationResult shift = findSpatialPeak(
      C, SpatialPeakRefinement::kGaussian, p.num_threads, volume != nullptr);
  if (volume)
    *volume = whitening > 0.0 ? std::move(plain) : std::move(C);
  e.translation_ms += msSince(t);
  return shift;
}

/** Everything one estimate needs about the source. */
struct SourceContext {
  const TargetModel& target;
  const Eigen::Matrix3Xd& points;
  const ChannelValues& channels;
  const PhaserParameters& p;
  VerificationSamples samples; ///< evenly spaced source points for verifyPose
  SurfacePatches patches;      ///< planar patches of the source (coarse voxels)
  FreeSpace free_space;        ///< what the source's sensor saw through
};

PoseVerification verify(const SourceContext& s, const Eigen::Matrix3d& R,
                        const Eigen::Vector3d& t, PhaserEstimate& e)
{
  const auto start = Clock::now();
  PoseVerification v = verifyPose(s.target.index, s.samples, R, t, s.p.num_threads,
                                  s.p.sensor_centred ? &s.target.free_space : nullptr);
  // The other way: target samples in space the source's sensor saw through.
  if (s.p.sensor_centred)
    v.reverse_free_space_violation =
        freeSpaceViolation(s.free_space, s.target.samples, s.target.sample_weights,
                           R.transpose(), -(R.transpose() * t), s.p.num_threads);
  e.verification_ms += msSince(start);
  return v;
}

/** Rotation hypotheses: the distinct peaks of the range correlation \a C and of the
 *  orientation histograms' correlation. */
std::vector<RotationHypothesis> rotationHypotheses(const SourceContext& s,
                                                   const So3CorrelationGrid& C,
                                                   double h_norm, PhaserEstimate& e)
{
  const PhaserParameters& p = s.p;
  std::vector<So3GridIndex> peaks;
  if (p.rotation_candidates > 1)
    peaks =
        distinctPeaks(C, p.rotation_candidates, kHypothesisSeparation, p.num_threads);
  if (peaks.empty())
    peaks.push_back(C.argmax(p.num_threads));
  std::vector<RotationHypothesis> out;
  for (const So3GridIndex& peak : peaks) {
    RotationHypothesis h;
    h.rotation = rotationFromEuler(gridEuler(peak, p.bandwidth));
    h.rotation_score = C(peak) / (s.target.spherical_norm * h_norm);
    out.push_back(h);
  }
  if (!p.sensor_centred || p.orientation_candidates == 0 ||
      s.target.orientation.size() == 0)
    return out;
  const auto t = Clock::now();
  const SphericalSpectrum O =
      orientationSpectrum(s.patches, p.orientation_bandwidth, p.num_threads);
  const So3CorrelationGrid Co = So3Correlator::instance(p.orientation_bandwidth)
                                    ->correlate(s.target.orientation, O, p.num_threads);
  const double norm =
      std::sqrt(spectrumSquaredNorm(s.target.orientation) * spectrumSquaredNorm(O));
  for (const So3GridIndex& peak : distinctPeaks(Co, p.orientation_candidates,
                                                kHypothesisSeparation, p.num_threads)) {
    RotationHypothesis h;
    h.rotation = rotationFromEuler(gridEuler(peak, p.orientation_bandwidth));
    h.rotation_score = norm > 0.0 ? Co(peak) / norm : 0.0;
    h.from_orientation = true;
    out.push_back(h);
  }
  e.orientation_ms += msSince(t);
  return out;
}

/** How a verified pose ranks: its closeness-weighted inlier share less a multiple of
 *  its free-space violations. A sample in space the target saw through is strong
 *  evidence against the pose; a sample without a target neighbour is weak (occlusion,
 *  partial overlap), hence the factor. */
double rank(const PoseVerification& v)
{
  return v.score - kViolationWeight *
                       std::max(v.free_space_violation, v.reverse_free_space_violation);
}

/** Whether a refined pose replaces the current one: when the poses are ranked by
 *  verification, if it ranks no worse; otherwise always (the passes' own stop rule
 *  decides). */
bool accept(const Pose& next, const Pose& current)
{
  return !current.verifiable || rank(next.v) >= rank(current.v);
}

/** Whether verification can tell poses apart: about sensor origins, with surfaces
 *  thinner than a third of the verification radius in both clouds (noise thicker than
 *  that lets wrong poses put as many samples within the radius as the right one). */
bool canVerify(const SourceContext& s)
{
  const double limit = kMaxThickness * s.target.index.radius();
  return s.p.sensor_centred && s.patches.thickness <= limit &&
         s.target.thickness <= limit;
}

/** Pass 1: every hypothesis through the coarse translation search and verification.
 *  About sensor origins, when at least one hypothesis puts kMinRankingInliers of the
 *  samples on the target, the best verified one wins. Otherwise (object scans, or
 *  clouds so noisy or sparse that no pose verifies, e.g. 1 m of noise at 40 dB PSNR)
 *  verification cannot rank them: the range peak whose rotated source overlaps the
 *  target most wins, as the orientation histograms are as unreliable as the normals. */
Pose globalSearch(const SourceContext& s, const So3CorrelationGrid& C, double h_norm,
                  PhaserEstimate& e)
{
  e.hypotheses = rotationHypotheses(s, C, h_norm, e);
  std::vector<PoseVerification> v(e.hypotheses.size());
  bool verifiable = false;
  for (std::size_t k = 0; k < e.hypotheses.size(); ++k) {
    RotationHypothesis& h = e.hypotheses[k];
    const SpatialCorrelationResult shift =
        shiftOf(s.target.coarse, h.rotation * s.points, s.p.whitening, s.p, e);
    h.translation = shift.shift;
    h.overlap = shift.peak_value;
    v[k] = verify(s, h.rotation, h.translation, e);
    h.inlier_fraction = v[k].inlier_fraction;
    h.verification_score = v[k].score;
    h.free_space_violation = v[k].free_space_violation;
    verifiable = verifiable || v[k].inlier_fraction >= kMinRankingInliers;
  }
  verifiable = verifiable && canVerify(s);
  std::size_t best = 0;
  for (std::size_t k = 1; k < e.hypotheses.size(); ++k) {
    const RotationHypothesis& h = e.hypotheses[k];
    const bool better =
        verifiable ? rank(v[k]) > rank(v[best])
                   : !h.from_orientation && h.overlap > e.hypotheses[best].overlap;
    if (better)
      best = k;
  }
  e.chosen_hypothesis = static_cast<int>(best);
  e.passes = 1;
  Pose pose{e.hypotheses[best].rotation, e.hypotheses[best].translation, v[best]};
  pose.verifiable = verifiable;
  return pose;
}

/** Later passes: the source, moved by the estimate, is seen from the target's centre,
 *  so its range function no longer suffers the parallax of the source's viewpoint; the
 *  residual rotation (grid argmax) and a fine-grid shift are composed with the
 *  estimate, kept only while verification does not get worse. A pass whose shift
 *  update is below a quarter of a fine voxel started from the right viewpoint: stop. */
Pose reprojectionPasses(const SourceContext& s, Pose pose, PhaserEstimate& e)
{
  const double settled = 0.25 * s.target.fine.grid.voxel_size;
  for (int pass = 1; pass < s.p.passes; ++pass) {
    const SphericalSpectrum H =
        sourceSpectrum((pose.R * s.points).colwise() + pose.t, s.channels, s.p, e);
    auto C =
        std::make_shared<So3CorrelationGrid>(correlateRotation(s.target, H, s.p, e));
    Pose next;
    next.verifiable = pose.verifiable;
    next.peak = C->argmax(s.p.num_threads);
    next.grid = C;
    const Eigen::Matrix3d dR = rotationFromEuler(gridEuler(next.peak, s.p.bandwidth));
    next.R = dR * pose.R;
    next.t = dR * pose.t;
    const Eigen::Vector3d shift =
        shiftOf(s.target.fine, (next.R * s.points).colwise() + next.t, 0.0, s.p, e)
            .shift;
    next.t += shift;
    next.v = verify(s, next.R, next.t, e);
    if (!accept(next, pose))
      break;
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
  const PhaserParameters& p = s.p;
  SphericalSupport support;
  const SphericalSpectrum H =
      sourceSpectrum((pose.R * s.points).colwise() + pose.t, s.channels, p, e,
                     p.normalized_refinement ? &support : nullptr);
  // After an accepted pass the residual is within the grid spacing: refine from the
  // identity; else search the grid from this viewpoint first.
  Eigen::Matrix3d start = Eigen::Matrix3d::Identity();
  if (!pose.grid) {
    pose.grid =
        std::make_shared<So3CorrelationGrid>(correlateRotation(target, H, p, e));
    pose.peak = pose.grid->argmax(p.num_threads);
    start = rotationFromEuler(gridEuler(pose.peak, p.bandwidth));
  }
  const So3CorrelationGrid& C = *pose.grid;
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
  next.t += shift.shift;
  next.v = verify(s, next.R, next.t, e);
  e.translation_score = shift.score;
  e.normalized_overlap =
      normalizedPeak(volume.values.empty() ? 0.0 : volumeAt(volume, shift.index),
                     grid_energy * energy);
  e.translation_covariance =
      translationCovariance(volume, shift.index, grid_energy * energy);
  rotationSamples(C, peak, dR * pose.R, e);
  e.rotation_score =
      value / (target.spherical_norm * std::sqrt(spectrumSquaredNorm(H)));
  if (accept(next, pose))
    pose = next;
  e.rotation = pose.R;
  e.translation = pose.t;
  e.inlier_fraction = pose.v.inlier_fraction;
  e.free_space_violation = pose.v.free_space_violation;
  e.constraint = pose.v.constraint;
  e.verification_samples = static_cast<int>(s.samples.points.cols());
  e.verified = e.verification_samples >= kMinVerificationSamples &&
               (!p.sensor_centred ||
                (pose.verifiable && e.inlier_fraction >= p.min_inlier_fraction &&
                 e.constraint >= p.min_constraint &&
                 e.free_space_violation <= p.max_free_space_violation));
  e.verification_score = pose.v.score;
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
  if (p.orientation_candidates < 0 || p.orientation_candidates > 10)
    return "number of orientation candidates must be in [0, 10], got " +
           std::to_string(p.orientation_candidates);
  if (p.orientation_bandwidth < 8 || p.orientation_bandwidth > 128)
    return "orientation bandwidth must be in [8, 128], got " +
           std::to_string(p.orientation_bandwidth);
  if (!(p.whitening >= 0.0 && p.whitening <= 1.0))
    return "whitening must be in [0, 1], got " + std::to_string(p.whitening);
  if (!(p.min_inlier_fraction >= 0.0 && p.min_inlier_fraction <= 1.0))
    return "minimum inlier fraction must be in [0, 1], got " +
           std::to_string(p.min_inlier_fraction);
  if (!(p.max_free_space_violation >= 0.0 && p.max_free_space_violation <= 1.0))
    return "maximum free-space violation must be in [0, 1], got " +
           std::to_string(p.max_free_space_violation);
  if (!(p.min_constraint >= 0.0 && p.min_constraint <= 1.0))
    return "minimum constraint must be in [0, 1], got " +
           std::to_string(p.min_constraint);
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
  coarse_grid.voxel_size = params.voxel_size;
  const SpatialGrid coarse = makeSpatialGrid(points, coarse_grid);
  model->coarse = occupancySpectrum(coarse, points, params.num_threads);
  model->coarse_energy = spectrumEnergy(model->coarse);
  const SurfacePatches patches =
      surfacePatches(points, kPatchVoxels * coarse.voxel_size, Eigen::Vector3d::Zero());
  if (params.orientation_candidates > 0 && params.sensor_centred)
    model->orientation =
        orientationSpectrum(patches, params.orientation_bandwidth, params.num_threads);
  model->thickness = patches.thickness;
  model->index = PointIndex(points, kVerificationVoxels * coarse.voxel_size,
                            patchNormalsAt(patches, points));
  if (params.sensor_centred) {
    model->samples = voxelCentroids(points, model->index.radius());
    model->sample_weights = orientationWeights(patches, model->samples);
  }
  if (params.sensor_centred)
    model->free_space =
        freeSpace(points, kFreeSpaceBandwidth, kFreeSpaceMargin * coarse.voxel_size,
                  params.num_threads);
  if (params.passes > 1) {
    const std::vector<Eigen::Index> keep = innerRegion(points);
    Eigen::Matrix3Xd inner(3, keep.size());
    for (std::size_t i = 0; i < keep.size(); ++i)
      inner.col(i) = points.col(keep[i]);
    SpatialGridParameters fine_grid = gridParameters(params);
    fine_grid.padding = 0.1;
    fine_grid.min_margin = 2.0 * fine_grid.padding * inner.cwiseAbs().maxCoeff();
    model->fine =
        occupancySpectrum(makeSpatialGrid(inner, fine_grid), inner, params.num_threads);
    model->fine_energy = spectrumEnergy(model->fine);
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
  const PhaserParameters& m = target.params;
  if (m.bandwidth != p.bandwidth || m.spatial_grid_size != p.spatial_grid_size ||
      m.voxel_size != p.voxel_size || m.passes != p.passes ||
      m.normalized_refinement != p.normalized_refinement ||
      m.orientation_candidates != p.orientation_candidates ||
      m.orientation_bandwidth != p.orientation_bandwidth ||
      m.sensor_centred != p.sensor_centred)
    throw InvalidArgument("the target model was prepared with other parameters");
  if (p.passes > 1 && target.fine.coefficients.empty())
    throw InvalidArgument("the target model was prepared for a single pass");
  if (raw_channels.size() != target.channels)
    throw InvalidArgument("the source has " + std::to_string(raw_channels.size()) +
                          " channels, the target " + std::to_string(target.channels));
  const ChannelValues channels = normalizeChannels(raw_channels, points.cols());
  PhaserEstimate e;
  e.verification_radius = target.index.radius();
  const auto t = Clock::now();
  SourceContext s{target, points, channels, p, {}, {}};
  s.samples.points = voxelCentroids(points, e.verification_radius);
  s.patches = surfacePatches(points, kPatchVoxels * target.coarse.grid.voxel_size,
                             Eigen::Vector3d::Zero());
  s.samples.weights = orientationWeights(s.patches, s.samples.points);
  s.samples.normals = patchNormalsAt(s.patches, s.samples.points);
  if (p.sensor_centred)
    s.free_space =
        freeSpace(points, kFreeSpaceBandwidth,
                  kFreeSpaceMargin * target.coarse.grid.voxel_size, p.num_threads);
  e.verification_ms += msSince(t);
  const SphericalSpectrum H = sourceSpectrum(points, channels, p, e);
  const So3CorrelationGrid C = correlateRotation(target, H, p, e);
  Pose pose = globalSearch(s, C, std::sqrt(spectrumSquaredNorm(H)), e);
  pose = reprojectionPasses(s, pose, e);
  finalStage(s, pose, e);
  return e;
}

} // namespace pcl_phaser
