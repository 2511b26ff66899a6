/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/phaser_registration.h>
#include <pcl_phaser/point_channels.h>

#include <pcl/common/point_tests.h>
#include <pcl/common/transforms.h>
#include <pcl/console/print.h>
#include <pcl/type_traits.h>

namespace pcl {

namespace phaser::detail {

/** \brief Appends channel \a C of \a p to \a values[k] when \a mask has it. */
template <Channel C, typename PointT>
void appendChannel(const PointT& p, std::uint32_t mask,
                   pcl::phaser::ChannelValues& values, std::size_t& k, Eigen::Index row)
{
  if constexpr ((availableChannels<PointT>() & C) != 0) {
    if (mask & C)
      values[k++][row] = channelValue<C>(p);
  }
}

/** \brief The finite xyz of the selected points (all when \a indices is null), as
 *  doubles, and the values of the channels in \a mask (in Channel order). */
template <typename PointT, typename Indices>
Eigen::Matrix3Xd extractCloud(const PointCloud<PointT>& cloud, const Indices* indices,
                              std::uint32_t mask, pcl::phaser::ChannelValues& values)
{
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
    out.col(count) = Eigen::Vector3d(p.x, p.y, p.z);
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

} // namespace phaser::detail

template <typename PointSource, typename PointTarget, typename Scalar>
void PhaserRegistration<PointSource, PointTarget, Scalar>::setInputSource(
    const PointCloudSourceConstPtr& cloud)
{
  converged_ = false;
  if (!cloud || cloud->empty()) {
    // Drop the previous cloud so that the next align cannot silently reuse it.
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
  target_model_.reset();
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
void PhaserRegistration<PointSource, PointTarget, Scalar>::setValid(
    const pcl::phaser::PhaserParameters& params, const char* setter)
{
  const std::string problem = pcl::phaser::validateParameters(params);
  if (!problem.empty()) {
    PCL_ERROR("[pcl::%s::%s] %s; the previous settings are kept.\n",
              getClassName().c_str(), setter, problem.c_str());
    return;
  }
  if (params.channels != params_.channels)
    target_model_.reset(); // other channels: extract the target again
  params_ = params;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void PhaserRegistration<PointSource, PointTarget, Scalar>::computeTransformation(
    PointCloudSource& output, const Matrix4& guess)
{
  rotation_uncertainty_.reset();
  if (!target_model_) {
    pcl::phaser::ChannelValues channels;
    Eigen::Matrix3Xd points = phaser::detail::extractCloud(
        *target_, static_cast<const Indices*>(nullptr), getFusedChannels(), channels);
    target_model_ = std::make_shared<const pcl::phaser::Target>(std::move(points),
                                                                std::move(channels));
  }
  pcl::phaser::SourceCloud source;
  source.points = phaser::detail::extractCloud(*input_, indices_.get(),
                                               getFusedChannels(), source.channels);
  result_ = pcl::phaser::align(*target_model_, source, guess.template cast<double>(),
                               params_);
  if (source.points.cols() == 0 && !this->fake_indices_) // not the cloud's fault
    result_.error =
        "the indices given to setIndices (" + std::to_string(indices_->size()) +
        ") select no finite source point; pass indices of finite points, or "
        "none to use the whole cloud";
  const pcl::phaser::PhaserDiagnostics& diagnostics = result_.diagnostics;
  if (!result_.error.empty())
    PCL_ERROR("[pcl::%s::computeTransformation] %s\n", getClassName().c_str(),
              result_.error.c_str());
  else if (!result_.converged)
    PCL_DEBUG("[pcl::%s::computeTransformation] not verified: inlier fraction %g, "
              "free-space violations %g / %g (source / target samples), %d samples, "
              "peak score %g: not converged\n",
              getClassName().c_str(), diagnostics.verification.inlier_fraction,
              diagnostics.verification.free_space_violation,
              diagnostics.verification.reverse_free_space_violation,
              diagnostics.verification_samples, diagnostics.translation_score);
  converged_ = result_.converged;
  final_transformation_ = transformation_ = result_.transformation.cast<Scalar>();
  phaser::detail::transformWhole(*input_, output, final_transformation_);
}

template <typename PointSource, typename PointTarget, typename Scalar>
const pcl::phaser::BinghamDistribution&
PhaserRegistration<PointSource, PointTarget, Scalar>::getRotationUncertainty() const
{
  if (!rotation_uncertainty_)
    rotation_uncertainty_ = std::make_shared<pcl::phaser::BinghamDistribution>(
        pcl::phaser::rotationUncertainty(result_));
  return *rotation_uncertainty_;
}

template <typename PointSource, typename PointTarget, typename Scalar>
Eigen::Matrix<double, 6, 6>
PhaserRegistration<PointSource, PointTarget, Scalar>::getCovariance() const
{
  if (!converged_) // e.g. a new source since the last align()
    return Eigen::Matrix<double, 6, 6>::Zero();
  return result_.covariance;
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
