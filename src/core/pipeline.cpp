/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include <pcl_phaser/core/error.h>
#include <pcl_phaser/core/pipeline.h>
#include <pcl_phaser/core/so3_correlation.h>
#include <pcl_phaser/core/so3_refinement.h>
#include <pcl_phaser/core/spatial_correlation.h>
#include <pcl_phaser/core/spherical_harmonics.h>
#include <pcl_phaser/core/spherical_sampling.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace pcl_phaser {

namespace {

using Clock = std::chrono::steady_clock;

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

/** Spectrum of a cloud on the sphere; throws when the cloud carries no spherical
 * signal. */
SphericalSpectrum sphericalSpectrum(const Eigen::Matrix3Xd& points,
                                    const PhaserParameters& p, const char* which,
                                    double* sampling_ms, double* sht_ms)
{
  auto t = Clock::now();
  const SphericalSamples samples =
      sampleSphere(points, p.bandwidth, nullptr, p.num_threads);
  if (sampling_ms)
    *sampling_ms = msSince(t);
  if (samples.observed_cells < 2)
    throw InvalidArgument(
        std::string(which) +
        " cloud has fewer than two distinct directions from its "
        "projection centre (empty, all at the centre, or a single point)");
  t = Clock::now();
  SphericalSpectrum F = SphericalHarmonicTransform::instance(p.bandwidth)
                            ->forward(samples.values.data(), p.num_threads);
  if (sht_ms)
    *sht_ms = msSince(t);
  if (!(spectrumSquaredNorm(F) > 0.0))
    throw InvalidArgument(std::string(which) + " cloud is constant on the sphere");
  return F;
}

} // namespace

class TargetModel {
public:
  PhaserParameters params;
  SphericalSpectrum spherical;
  double spherical_norm = 0.0;
  SpatialSpectrum coarse; ///< whole target, padded: any shift up to half the extent
  SpatialSpectrum fine; ///< inner region, little padding: the residual of later passes
  double preparation_ms = 0.0;
};

namespace {

/** Rotation pass: spherical samples of the source, SO(3) correlation with the target's
 *  spectrum, best grid peak, Newton refinement. */
Eigen::Matrix3d estimateRotation(const TargetModel& target,
                                 const Eigen::Matrix3Xd& points,
                                 const PhaserParameters& p,
                                 const Eigen::Matrix3d& start, bool refine,
                                 PhaserEstimate& e)
{
  double sampling_ms = 0.0, sht_ms = 0.0;
  const SphericalSpectrum H =
      sphericalSpectrum(points, p, "source", &sampling_ms, &sht_ms);
  e.sampling_ms += sampling_ms;
  e.sht_ms += sht_ms;
  Eigen::Matrix3d R = start;
  double value = 0.0;
  if (start.isZero()) { // no start given: the global search on the SO(3) grid
    const auto t = Clock::now();
    const So3CorrelationGrid C = So3Correlator::instance(p.bandwidth)
                                     ->correlate(target.spherical, H, p.num_threads);
    const So3GridIndex peak = C.argmax();
    R = rotationFromEuler(gridEuler(peak, p.bandwidth));
    value = C(peak);
    e.so3_ms += msSince(t);
  }
  if (refine && p.refinement_iterations > 0) {
    const auto t = Clock::now();
    const RefinedRotation refined = refineRotation(
        target.spherical, H, R, p.bandwidth, p.refinement_iterations, p.num_threads);
    R = refined.rotation;
    value = refined.value;
    e.refinement_ms += msSince(t);
  } else if (!start.isZero()) {
    value = evaluateCorrelation(target.spherical, H, {R}, p.num_threads)[0];
  }
  e.rotation_score =
      value / (target.spherical_norm * std::sqrt(spectrumSquaredNorm(H)));
  return R;
}

/** Translation pass: the (already rotated) source voxelised into the grid of \a target,
 *  3-D correlation, sub-voxel peak. */
Eigen::Vector3d estimateShift(const SpatialSpectrum& target,
                              const Eigen::Matrix3Xd& points, const PhaserParameters& p,
                              PhaserEstimate& e)
{
  const auto t = Clock::now();
  SpatialVoxelParameters voxel_params;
  voxel_params.num_threads = p.num_threads;
  const SpatialSpectrum S =
      computeSpectrum(voxelize(target.grid, points, voxel_params));
  const SpatialCorrelationResult shift =
      correlateSpatial(target, S, SpatialPeakRefinement::kGaussian, p.num_threads);
  e.translation_score = shift.score;
  e.translation_ms += msSince(t);
  return shift.shift;
}

/** The target points inside the cube that holds the inner 75% of them (by distance from
 *  the centre): after the first pass the residual shift is small, so a fine grid over
 *  the densely observed region measures it best. */
Eigen::Matrix3Xd innerRegion(const Eigen::Matrix3Xd& points)
{
  std::vector<double> r(points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    r[i] = points.col(i).cwiseAbs().maxCoeff();
  std::vector<double> sorted = r;
  const std::size_t k = (sorted.size() * 3) / 4;
  std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
  const double half = sorted[k];
  Eigen::Matrix3Xd inner(3, points.cols());
  Eigen::Index n = 0;
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    if (r[i] <= half)
      inner.col(n++) = points.col(i);
  inner.conservativeResize(3, n);
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
  if (p.passes < 1 || p.passes > 5)
    return "number of passes must be in [1, 5], got " + std::to_string(p.passes);
  if (p.num_threads < 1 || p.num_threads > 64)
    return "number of threads must be in [1, 64], got " + std::to_string(p.num_threads);
  return {};
}

std::shared_ptr<const TargetModel> prepareTarget(const Eigen::Matrix3Xd& points,
                                                 const PhaserParameters& params)
{
  const std::string problem = validateParameters(params);
  if (!problem.empty())
    throw InvalidArgument(problem);
  const auto start = Clock::now();
  auto model = std::make_shared<TargetModel>();
  model->params = params;
  model->spherical = sphericalSpectrum(points, params, "target", nullptr, nullptr);
  model->spherical_norm = std::sqrt(spectrumSquaredNorm(model->spherical));
  SpatialVoxelParameters voxel_params;
  voxel_params.num_threads = params.num_threads;
  SpatialGridParameters coarse_grid;
  coarse_grid.grid_size = params.spatial_grid_size;
  model->coarse = computeSpectrum(
      voxelize(makeSpatialGrid(points, coarse_grid), points, voxel_params));
  if (params.passes > 1) {
    const Eigen::Matrix3Xd inner = innerRegion(points);
    SpatialGridParameters fine_grid = gridParameters(params);
    fine_grid.padding = 0.1;
    fine_grid.min_margin = 2.0 * fine_grid.padding * inner.cwiseAbs().maxCoeff();
    model->fine = computeSpectrum(
        voxelize(makeSpatialGrid(inner, fine_grid), inner, voxel_params));
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
                                 const PhaserParameters& p)
{
  const std::string problem = validateParameters(p);
  if (!problem.empty())
    throw InvalidArgument(problem);
  if (target.params.bandwidth != p.bandwidth ||
      target.params.spatial_grid_size != p.spatial_grid_size ||
      target.params.voxel_size != p.voxel_size || target.params.passes != p.passes)
    throw InvalidArgument("the target model was prepared with other parameters");
  if (p.passes > 1 && target.fine.coefficients.empty())
    throw InvalidArgument("the target model was prepared for a single pass");
  PhaserEstimate e;

  // Pass 1: rotation about the source's own centre, the shift on the coarse grid, then
  // (with more passes) the residual shift on the fine grid.
  const bool single = p.passes == 1;
  Eigen::Matrix3d R =
      estimateRotation(target, points, p, Eigen::Matrix3d::Zero(), single, e);
  Eigen::Vector3d t = estimateShift(target.coarse, R * points, p, e);
  e.passes = 1;
  if (single) {
    e.rotation = R;
    e.translation = t;
    return e;
  }
  t += estimateShift(target.fine, (R * points).colwise() + t, p, e);
  // Later passes: the source, moved by the estimate, is seen from the target's centre,
  // so its range function no longer suffers the parallax of the source's viewpoint; the
  // residual rotation and a fine-grid shift are composed with the estimate. A pass
  // whose shift update is below a quarter of a fine voxel started from the right
  // viewpoint, so another would not change the rotation: stop there.
  const double settled = 0.25 * target.fine.grid.voxel_size;
  for (int pass = 1; pass < p.passes; ++pass) {
    const Eigen::Matrix3d dR = estimateRotation(target, (R * points).colwise() + t, p,
                                                Eigen::Matrix3d::Zero(), false, e);
    R = dR * R;
    t = dR * t;
    const Eigen::Vector3d shift =
        estimateShift(target.fine, (R * points).colwise() + t, p, e);
    t += shift;
    e.passes = pass + 1;
    if (shift.norm() < settled)
      break;
  }
  // Finally the residual rotation from the final viewpoint, Newton-refined from the
  // identity (it is within the grid spacing by now), and the matching shift.
  const Eigen::Matrix3d dR = estimateRotation(target, (R * points).colwise() + t, p,
                                              Eigen::Matrix3d::Identity(), true, e);
  R = dR * R;
  t = dR * t;
  t += estimateShift(target.fine, (R * points).colwise() + t, p, e);
  e.rotation = R;
  e.translation = t;
  return e;
}

} // namespace pcl_phaser
