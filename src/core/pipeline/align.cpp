/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The engine's entry point in the caller's frames: input checks, the priors and the
 * stage settings, guess composition, the convergence decision and the covariance.
 */
#include "pipeline/stages.h"
#include "pipeline/target.h"
#include "priors/allowed_poses.h"
#include "support/buffer_pool.h"
#include "support/error.h"
#include "uncertainty/peak_neighborhood.h"

#include <pcl_phaser/core/bingham.h>
#include <pcl_phaser/core/pipeline.h>

#include <new>

namespace pcl::phaser {

namespace {

constexpr double kMaxCoordinate = 1e6; ///< beyond: float32 is coarser than 6 cm

/** Empty when a cloud can be registered, else why not. */
std::string checkCloud(const Eigen::Matrix3Xd& points, const ChannelValues& channels,
                       const char* which)
{
  if (points.cols() == 0)
    return std::string("the ") + which + " cloud has no finite points";
  if (!points.allFinite())
    return std::string("the ") + which + " cloud has non-finite points";
  if (points.cwiseAbs().maxCoeff() > kMaxCoordinate)
    return "coordinates beyond 1e6 m: float32 resolution is worse than 6 cm there; "
           "shift the clouds first (e.g. pcl::demeanPointCloud)";
  if ((points.colwise() - points.col(0)).isZero(0.0))
    return std::string("every finite point of the ") + which + " cloud (" +
           std::to_string(points.cols()) +
           ") is at one position: registration needs points spread over a scene";
  for (const Eigen::VectorXd& c : channels)
    if (c.size() != points.cols())
      return std::string("a channel of the ") + which + " cloud has " +
             std::to_string(c.size()) + " values for " + std::to_string(points.cols()) +
             " points";
  return {};
}

/** Empty when the inputs of align() are legal, else the first problem. */
std::string checkInputs(const Target& target, const SourceCloud& source,
                        const Eigen::Matrix4d& guess, const PhaserParameters& params)
{
  const ChannelValues& target_channels = TargetAccess::channels(target);
  std::string problem = validateParameters(params);
  if (problem.empty() && !guess.allFinite())
    problem = "the initial guess is not finite";
  if (problem.empty())
    problem = checkCloud(target.points(), target_channels, "target");
  if (problem.empty())
    problem = checkCloud(source.points, source.channels, "source");
  if (problem.empty() && source.channels.size() != target_channels.size())
    problem = "the source has " + std::to_string(source.channels.size()) +
              " channels, the target " + std::to_string(target_channels.size());
  return problem;
}

/** p_target = R (G p_source - c_s) + c_t + t, as a 4 x 4 matrix. */
Eigen::Matrix4d callerFrame(const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                            const Eigen::Vector3d& source_center,
                            const Eigen::Vector3d& target_center,
                            const Eigen::Matrix4d& guess)
{
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = R;
  T.topRightCorner<3, 1>() = target_center + t - R * source_center;
  return T * guess;
}

/** [a]x, the cross-product matrix of \a a. */
Eigen::Matrix3d skew(const Eigen::Vector3d& a)
{
  return (Eigen::Matrix3d() << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0)
      .finished();
}

/** \a pose and what \a result holds of it, found against the target model turned by
 *  \a axes, turned back to the target's axes. */
void turnBack(const Eigen::Matrix3d& axes, RigidPose& pose, PhaserResult& result)
{
  if (axes.isIdentity(0.0))
    return;
  const Eigen::Matrix3d back = axes.transpose();
  pose.R = back * pose.R;
  pose.t = back * pose.t;
  PhaserDiagnostics& diagnostics = result.diagnostics;
  for (Hypothesis& h : diagnostics.hypotheses) {
    h.rotation = back * h.rotation;
    h.translation = back * h.translation;
  }
  const Eigen::Quaterniond q_back(back);
  for (Eigen::Vector4d& s : diagnostics.rotation_samples) {
    const Eigen::Quaterniond q = q_back * Eigen::Quaterniond(s[0], s[1], s[2], s[3]);
    s = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
  }
  Eigen::Matrix<double, 6, 6> B = Eigen::Matrix<double, 6, 6>::Zero();
  B.topLeftCorner<3, 3>() = back;
  B.bottomRightCorner<3, 3>() = back;
  result.fit_covariance = B * result.fit_covariance * B.transpose();
  result.translation_covariance =
      back * result.translation_covariance * back.transpose();
}

/** Verified and, about centroids, a distinct peak (half the score with a clear overlap:
 *  scans meters apart give wider peaks). */
bool converged(const PhaserResult& result, const PhaserParameters& params)
{
  const PhaserDiagnostics& diagnostics = result.diagnostics;
  const bool peak = diagnostics.translation_score >= params.min_peak_score ||
                    (diagnostics.translation_score >= 0.5 * params.min_peak_score &&
                     diagnostics.normalized_overlap >= params.min_normalized_overlap);
  return diagnostics.verified &&
         (result.projection_center == ProjectionCenter::SensorOrigin || peak);
}

/** align() on legal inputs. \throws InvalidArgument when a cloud has no signal. */
PhaserResult alignChecked(const Target& target, const SourceCloud& source,
                          const Eigen::Matrix4d& guess, const PhaserParameters& params)
{
  Eigen::Matrix3Xd moved(3, source.points.cols());
  for (Eigen::Index i = 0; i < moved.cols(); ++i)
    moved.col(i) = guess.topLeftCorner<3, 3>() * source.points.col(i) +
                   guess.topRightCorner<3, 1>();
  const detail::AllowedPoses allowed = detail::allowedPoses(params, moved, guess);
  const ProjectionCenter center =
      allowed.region
          ? ProjectionCenter::SensorOrigin
          : detail::chooseCenter(target, moved, guess, params.projection_center);
  const detail::StageSettings settings = detail::stageSettings(
      params,
      detail::stageMode(target, moved, guess, center, allowed.region.has_value()),
      allowed);
  PhaserResult result;
  Eigen::Vector3d target_center;
  Eigen::Matrix3d axes;
  const std::shared_ptr<const detail::TargetModel> model =
      detail::targetModel(target, center, settings, allowed.region, target_center, axes,
                          result.diagnostics.times.target);
  const Eigen::Vector3d source_center =
      center == ProjectionCenter::Centroid
          ? Eigen::Vector3d(moved.rowwise().mean())
          : Eigen::Vector3d(guess.topRightCorner<3, 1>());
  moved.colwise() -= source_center;
  RigidPose pose = detail::estimateCentered(*model, moved, settings, allowed,
                                            source.channels, result);
  turnBack(axes, pose, result);
  result.projection_center = center;
  result.transformation =
      callerFrame(pose.R, pose.t, source_center, target_center, guess);
  if (!result.transformation.allFinite())
    throw InvalidArgument("the estimate is not finite");
  result.lever_arm = pose.R * source_center;
  // fitCovariance's error q -> Exp(omega) q + nu0 about the target's center for the
  // caller's nu = t_true - t_est = nu0 + omega x a, a: the translation from there.
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Identity();
  A.bottomLeftCorner<3, 3>() =
      -skew(result.transformation.topRightCorner<3, 1>() - target_center);
  result.fit_covariance = A * result.fit_covariance * A.transpose();
  for (Hypothesis& h : result.diagnostics.hypotheses)
    h.transformation =
        callerFrame(h.rotation, h.translation, source_center, target_center, guess);
  result.converged = converged(result, params);
  detail::keepAllowed(result, allowed);
  result.covariance =
      poseCovariance(result, rotationUncertainty(result), params.bandwidth);
  return result;
}

PhaserResult failed(const Eigen::Matrix4d& guess, std::string reason)
{
  PhaserResult result;
  result.transformation = guess;
  result.error = std::move(reason);
  return result;
}

} // namespace

PhaserResult align(const Target& target, const SourceCloud& source,
                   const Eigen::Matrix4d& guess, const PhaserParameters& params)
{
  const std::string problem = checkInputs(target, source, guess, params);
  if (!problem.empty())
    return failed(guess, problem);
  try {
    const detail::BufferPoolScope reuse_buffers;
    return alignChecked(target, source, guess, params);
  } catch (const InvalidArgument& e) {
    return failed(guess, e.what());
  } catch (const std::bad_alloc&) {
    return failed(guess, "out of memory (reduce the bandwidth or the grid size)");
  }
}

BinghamDistribution rotationUncertainty(const PhaserResult& result)
{
  const PhaserDiagnostics& diagnostics = result.diagnostics;
  try {
    if (!diagnostics.rotation_samples.empty())
      return fitBingham(diagnostics.rotation_samples, diagnostics.rotation_weights);
  } catch (const InvalidArgument&) { // all weights zero: a flat block
  }
  return BinghamDistribution(); // uniform: what is known without an estimate
}

Eigen::Matrix<double, 6, 6> poseCovariance(const PhaserResult& result,
                                           const BinghamDistribution& rotation,
                                           int bandwidth)
{
  Eigen::Matrix<double, 6, 6> cov = Eigen::Matrix<double, 6, 6>::Zero();
  if (!result.converged)
    return cov;
  if (!result.fit_covariance.isZero())
    return result.fit_covariance;
  const Eigen::Matrix3d rot = rotationCovariance(rotation, bandwidth);
  // t_est = c_t + delta - R c_s, R_true = Exp(omega) R_est: nu = d_delta + [R c_s]x
  // omega
  const Eigen::Matrix3d lever = skew(result.lever_arm);
  cov.topLeftCorner<3, 3>() = rot;
  cov.topRightCorner<3, 3>() = rot * lever.transpose();
  cov.bottomLeftCorner<3, 3>() = lever * rot;
  cov.bottomRightCorner<3, 3>() =
      result.translation_covariance + lever * rot * lever.transpose();
  return cov;
}

} // namespace pcl::phaser
