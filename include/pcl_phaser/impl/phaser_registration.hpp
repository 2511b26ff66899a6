/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/core/error.h>
#include <pcl_phaser/core/peak_neighbourhood.h>
#include <pcl_phaser/phaser_registration.h>
#include <pcl_phaser/point_channels.h>

#include <pcl/common/point_tests.h>
#include <pcl/common/transforms.h>
#include <pcl/console/print.h>
#include <pcl/type_traits.h>

#include <cmath>
#include <new>

namespace pcl {

namespace phaser_detail {

using namespace pcl::phaser;

/** \brief Beyond this, float32 coordinates are quantised to more than 6 cm. */
constexpr float kMaxCoordinate = 1e6f;

constexpr const char* kTooFar = "coordinates beyond 1e6 m: float32 resolution is worse "
                                "than 6 cm there; shift the clouds first (e.g. "
                                "pcl::demeanPointCloud)";

/** \brief Appends the value of channel \a C of \a p to \a values[k] when the mask has
 * it. */
template <Channel C, typename PointT>
void appendChannel(const PointT& p, std::uint32_t mask,
                   pcl_phaser::ChannelValues& values, std::size_t& k, Eigen::Index row)
{
  if constexpr ((availableChannels<PointT>() & C) != 0) {
    if (mask & C)
      values[k++][row] = channelValue<C>(p);
  }
}

/** \brief Finite xyz of the selected points, as doubles, mapped by \a T, and the values
 * of the channels in \a mask (in Channel order); \a too_far is set when a coordinate
 *  exceeds kMaxCoordinate. */
template <typename PointT, typename Indices>
Eigen::Matrix3Xd extractCloud(const PointCloud<PointT>& cloud, const Indices* indices,
                              const Eigen::Matrix4d& T, std::uint32_t mask,
                              pcl_phaser::ChannelValues& values, bool& too_far)
{
  too_far = false;
  const std::size_t n = indices ? indices->size() : cloud.size();
  mask &= availableChannels<PointT>() & ~static_cast<std::uint32_t>(CHANNEL_RANGE);
  values.assign(static_cast<std::size_t>(__builtin_popcount(mask)),
                Eigen::VectorXd(static_cast<Eigen::Index>(n)));
  Eigen::Matrix3Xd out(3, n);
  Eigen::Index count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const PointT& p = cloud[indices ? static_cast<std::size_t>((*indices)[i]) : i];
    if (!isXYZFinite(p))
      continue;
    too_far = too_far || std::abs(p.x) > kMaxCoordinate ||
              std::abs(p.y) > kMaxCoordinate || std::abs(p.z) > kMaxCoordinate;
    const Eigen::Vector3d q(p.x, p.y, p.z);
    out.col(count) = T.topLeftCorner<3, 3>() * q + T.topRightCorner<3, 1>();
    std::size_t k = 0;
    appendChannel<CHANNEL_INTENSITY>(p, mask, values, k, count);
    appendChannel<CHANNEL_REFLECTIVITY>(p, mask, values, k, count);
    appendChannel<CHANNEL_AMBIENT>(p, mask, values, k, count);
    appendChannel<CHANNEL_COLOR>(p, mask, values, k, count);
    ++count;
  }
  out.conservativeResize(3, count);
  for (Eigen::VectorXd& v : values)
    v.conservativeResize(count);
  return out;
}

template <typename PointT, typename Scalar>
void transformWhole(const PointCloud<PointT>& in, PointCloud<PointT>& out,
                    const Eigen::Matrix<Scalar, 4, 4>& T)
{
  if constexpr (traits::has_normal_v<PointT>)
    transformPointCloudWithNormals(in, out, T);
  else
    transformPointCloud(in, out, T);
}

} // namespace phaser_detail

template <typename PointSource, typename PointTarget, typename Scalar>
void PhaserRegistration<PointSource, PointTarget, Scalar>::setInputSource(
    const PointCloudSourceConstPtr& cloud)
{
  converged_ = false;
  if (!cloud || cloud->empty()) {
    // pcl::Registration would keep the previous cloud (or dereference null): refuse,
    // and drop the previous one so that the next align cannot silently reuse it.
    PCL_ERROR("[pcl::%s::setInputSource] The source cloud is null or empty.\n",
              getClassName().c_str());
    input_.reset();
    return;
  }
  if (!cloud->is_dense)
    PCL_WARN(
        "[pcl::%s::setInputSource] The source cloud is not dense; non-finite points "
        "are skipped.\n",
        getClassName().c_str());
  Base::setInputSource(cloud);
}

template <typename PointSource, typename PointTarget, typename Scalar>
void PhaserRegistration<PointSource, PointTarget, Scalar>::setInputTarget(
    const PointCloudTargetConstPtr& cloud)
{
  invalidateTarget();
  converged_ = false;
  if (!cloud || cloud->empty()) {
    PCL_ERROR("[pcl::%s::setInputTarget] The target cloud is null or empty.\n",
              getClassName().c_str());
    target_.reset();
    return;
  }
  if (!cloud->is_dense)
    PCL_WARN(
        "[pcl::%s::setInputTarget] The target cloud is not dense; non-finite points "
        "are skipped.\n",
        getClassName().c_str());
  Base::setInputTarget(cloud);
}

template <typename PointSource, typename PointTarget, typename Scalar>
bool PhaserRegistration<PointSource, PointTarget, Scalar>::extractTarget(
    Eigen::Matrix3Xd& points, pcl_phaser::ChannelValues& channels,
    std::string& problem) const
{
  bool too_far = false;
  points = phaser_detail::extractCloud(*target_, static_cast<const Indices*>(nullptr),
                                       Eigen::Matrix4d::Identity(), fusedChannels(),
                                       channels, too_far);
  if (points.cols() == 0)
    problem = "the target cloud has no finite points";
  else if (too_far)
    problem = phaser_detail::kTooFar;
  return problem.empty();
}

template <typename PointSource, typename PointTarget, typename Scalar>
void PhaserRegistration<PointSource, PointTarget, Scalar>::fail(
    PointCloudSource& output, const Matrix4& guess, const std::string& reason)
{
  PCL_ERROR("[pcl::%s::computeTransformation] %s\n", getClassName().c_str(),
            reason.c_str());
  converged_ = false;
  final_transformation_ = transformation_ = guess;
  phaser_detail::transformWhole(*input_, output, final_transformation_);
}

template <typename PointSource, typename PointTarget, typename Scalar>
void PhaserRegistration<PointSource, PointTarget, Scalar>::computeTransformation(
    PointCloudSource& output, const Matrix4& guess)
{
  converged_ = false;
  estimate_ = {};
  candidates_.clear();
  rotation_uncertainty_.reset();
  lever_arm_.setZero();
  const std::string problem = pcl_phaser::validateParameters(params_);
  if (!problem.empty())
    return fail(output, guess, problem);
  if (!(min_peak_score_ >= 0.0))
    return fail(output, guess, "the minimum peak score must be >= 0");
  if (!(min_normalized_overlap_ >= 0.0 && min_normalized_overlap_ <= 1.0))
    return fail(output, guess, "the minimum normalised overlap must be in [0, 1]");
  const Eigen::Matrix4d G = guess.template cast<double>();
  if (!G.allFinite())
    return fail(output, guess, "the initial guess is not finite");

  double target_ms = 0.0;
  Eigen::Vector3d source_center = Eigen::Vector3d::Zero();
  try {
    // Target: extracted when a model (or, for Automatic, its coverage) is missing.
    Eigen::Matrix3Xd tgt;
    pcl_phaser::ChannelValues target_channels;
    bool have_target = false;
    std::string reason;
    if (!target_model_ ||
        (center_ == ProjectionCenter::Automatic && target_sensor_centred_ < 0)) {
      if (!extractTarget(tgt, target_channels, reason))
        return fail(output, guess, reason);
      have_target = true;
      if (center_ == ProjectionCenter::Automatic)
        target_sensor_centred_ =
            pcl_phaser::looksSensorCentred(tgt, Eigen::Vector3d::Zero()) ? 1 : 0;
    }
    // Source: the points of indices_, finite, moved by the guess (its sensor origin
    // moves with the guess too).
    bool too_far = false;
    pcl_phaser::ChannelValues source_channels;
    Eigen::Matrix3Xd src = phaser_detail::extractCloud(
        *input_, indices_.get(), G, fusedChannels(), source_channels, too_far);
    if (src.cols() == 0)
      return fail(output, guess, "the source cloud has no finite points");
    if (too_far)
      return fail(output, guess, phaser_detail::kTooFar);
    used_center_ = center_;
    if (center_ == ProjectionCenter::Automatic)
      used_center_ = target_sensor_centred_ == 1 && pcl_phaser::looksSensorCentred(
                                                        src, G.topRightCorner<3, 1>())
                         ? ProjectionCenter::SensorOrigin
                         : ProjectionCenter::Centroid;
    // The tilt pull the normalised refinement corrects comes from a scanner's
    // field-of-view band, seen about its origin; about an object's centroid there is
    // none, and it measured worse there (bunny pair 6.7 -> 7.2 deg).
    pcl_phaser::PhaserParameters params = params_;
    params.normalized_refinement =
        params_.normalized_refinement && used_center_ == ProjectionCenter::SensorOrigin;
    params.sensor_centred = used_center_ == ProjectionCenter::SensorOrigin;
    // The target model: prepared once per target, parameter set and centre, relative
    // to the target's centre.
    if (!target_model_ || model_center_ != used_center_) {
      if (!have_target && !extractTarget(tgt, target_channels, reason))
        return fail(output, guess, reason);
      target_center_ = used_center_ == ProjectionCenter::Centroid
                           ? Eigen::Vector3d(tgt.rowwise().mean())
                           : Eigen::Vector3d::Zero();
      tgt.colwise() -= target_center_;
      target_model_ = pcl_phaser::prepareTarget(tgt, params, target_channels);
      model_center_ = used_center_;
      target_ms = pcl_phaser::preparationTime(*target_model_);
    }
    source_center = used_center_ == ProjectionCenter::Centroid
                        ? Eigen::Vector3d(src.rowwise().mean())
                        : Eigen::Vector3d(G.topRightCorner<3, 1>());
    src.colwise() -= source_center;
    estimate_ =
        pcl_phaser::estimateTransform(*target_model_, src, params, source_channels);
    estimate_.target_ms = target_ms;
  } catch (const pcl_phaser::InvalidArgument& e) {
    return fail(output, guess, e.what());
  } catch (const std::bad_alloc&) {
    return fail(output, guess, "out of memory (reduce the bandwidth or the grid size)");
  }
  // p_target = R (G p_source - c_s) + c_t + t
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = estimate_.rotation;
  T.topRightCorner<3, 1>() =
      target_center_ + estimate_.translation - estimate_.rotation * source_center;
  const Eigen::Matrix4d final_transform = T * G;
  if (!final_transform.allFinite())
    return fail(output, guess, "the estimate is not finite");
  final_transformation_ = transformation_ = final_transform.cast<Scalar>();
  lever_arm_ = estimate_.rotation * source_center;
  for (std::size_t k = 0; k < estimate_.hypotheses.size(); ++k) {
    const pcl_phaser::RotationHypothesis& h = estimate_.hypotheses[k];
    Eigen::Matrix4d C = Eigen::Matrix4d::Identity();
    C.topLeftCorner<3, 3>() = h.rotation;
    C.topRightCorner<3, 1>() =
        target_center_ + h.translation - h.rotation * source_center;
    Candidate candidate;
    candidate.transformation = (C * G).cast<Scalar>();
    candidate.rotation_score = h.rotation_score;
    candidate.overlap = h.overlap;
    candidate.chosen = static_cast<int>(k) == estimate_.chosen_hypothesis;
    candidates_.push_back(candidate);
  }
  // Converged means verified: the final pose puts enough source samples on the target
  // and, about sensor origins, few in space the target saw through. About centroids
  // (no free-space test) a distinct translation peak is also required; scans taken
  // metres apart give wider peaks, so a clear overlap lets half the score suffice.
  const bool peak = estimate_.translation_score >= min_peak_score_ ||
                    (estimate_.translation_score >= 0.5 * min_peak_score_ &&
                     estimate_.normalized_overlap >= min_normalized_overlap_);
  converged_ =
      estimate_.verified && (used_center_ == ProjectionCenter::SensorOrigin || peak);
  if (!converged_)
    PCL_DEBUG("[pcl::%s::computeTransformation] not verified: inlier fraction %g, "
              "free-space violation %g, %d samples, peak score %g: not converged\n",
              getClassName().c_str(), estimate_.inlier_fraction,
              estimate_.free_space_violation, estimate_.verification_samples,
              estimate_.translation_score);
  phaser_detail::transformWhole(*input_, output, final_transformation_);
}

template <typename PointSource, typename PointTarget, typename Scalar>
const pcl_phaser::BinghamDistribution&
PhaserRegistration<PointSource, PointTarget, Scalar>::getRotationUncertainty() const
{
  if (!rotation_uncertainty_) {
    pcl_phaser::BinghamDistribution b; // uniform: what is known without an estimate
    if (!estimate_.rotation_samples.empty()) {
      try {
        b = pcl_phaser::fitBingham(estimate_.rotation_samples,
                                   estimate_.rotation_weights);
      } catch (const pcl_phaser::InvalidArgument&) { // all weights zero: a flat block
      }
    }
    rotation_uncertainty_ = std::make_shared<pcl_phaser::BinghamDistribution>(b);
  }
  return *rotation_uncertainty_;
}

template <typename PointSource, typename PointTarget, typename Scalar>
Eigen::Matrix<double, 6, 6>
PhaserRegistration<PointSource, PointTarget, Scalar>::getCovariance() const
{
  Eigen::Matrix<double, 6, 6> cov = Eigen::Matrix<double, 6, 6>::Zero();
  if (!converged_)
    return cov;
  const Eigen::Matrix3d rot =
      pcl_phaser::rotationCovariance(getRotationUncertainty(), params_.bandwidth);
  // t_est = c_t + delta - R c_s, R_true = Exp(omega) R_est: nu = d_delta + [R c_s]x
  // omega.
  Eigen::Matrix3d lever;
  lever << 0, -lever_arm_.z(), lever_arm_.y(), lever_arm_.z(), 0, -lever_arm_.x(),
      -lever_arm_.y(), lever_arm_.x(), 0;
  cov.topLeftCorner<3, 3>() = rot;
  cov.topRightCorner<3, 3>() = rot * lever.transpose();
  cov.bottomLeftCorner<3, 3>() = lever * rot;
  cov.bottomRightCorner<3, 3>() =
      estimate_.translation_covariance + lever * rot * lever.transpose();
  return cov;
}

template <typename PointSource, typename PointTarget, typename Scalar>
double
PhaserRegistration<PointSource, PointTarget, Scalar>::getFitnessScore(double max_range)
{
  constexpr double none = std::numeric_limits<double>::max();
  if (!input_ || !target_ || !tree_ || !tree_->getInputCloud())
    return none;
  PointCloudSource transformed;
  transformPointCloud(*input_, transformed, final_transformation_);
  pcl::Indices nn_index(1);
  std::vector<float> nn_distance(1);
  double sum = 0.0;
  std::size_t count = 0;
  for (const PointSource& p : transformed) {
    if (!isXYZFinite(p))
      continue;
    PointTarget query;
    query.x = p.x;
    query.y = p.y;
    query.z = p.z;
    if (tree_->nearestKSearch(query, 1, nn_index, nn_distance) == 0)
      continue;
    if (nn_distance[0] <= max_range) {
      sum += nn_distance[0];
      ++count;
    }
  }
  return count ? sum / static_cast<double>(count) : none;
}

} // namespace pcl
