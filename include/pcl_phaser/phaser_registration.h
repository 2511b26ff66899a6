/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/core/pipeline.h>
#include <pcl_phaser/lazy_kdtree.h>
#include <pcl_phaser/point_channels.h>

#include <pcl/registration/registration.h>

#include <cstdint>
#include <limits>
#include <memory>

namespace pcl {

/** \brief PhaserRegistration: correspondence-free global registration of two point
 * clouds by spherical and spatial phase correlation (PHASER).
 *
 *  \details The rotation comes from correlating the spherical-harmonic spectra of the
 * two clouds, projected on the sphere about a center, on SO(3), beside the correlation
 * of their surface-orientation histograms; the translation from a 3-D FFT correlation
 * of the voxelized clouds. Every hypothesis is verified geometrically and the best one
 * wins; hasConverged() means the final pose verified (pcl::phaser::PhaserResult::
 * converged). No normals, features or correspondences are needed, so it replaces
 * pcl::SampleConsensusInitialAlignment as the global initializer ahead of
 * pcl::IterativeClosestPoint:
 *  \code
 *  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
 *  phaser.setInputSource(source);
 *  phaser.setInputTarget(target);
 *  pcl::PointCloud<pcl::PointXYZ> aligned;
 *  phaser.align(aligned);
 *  if (phaser.hasConverged()) {
 *    pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
 *    icp.setInputSource(source);
 *    icp.setInputTarget(target);
 *    icp.align(aligned, phaser.getFinalTransformation());
 *  }
 *  \endcode
 *
 *  Conventions: getFinalTransformation() maps source points into the target frame
 *  (p_target = T p_source). A \a guess passed to align() is applied to the source first
 *  and the estimate is composed with it. Non-finite points are skipped; \a indices_
 *  selects the source points used for the estimate, while the output is the whole
 *  transformed input, with normals rotated for point types that carry them. What
 *  depends only on the target (its spectra) is cached until setInputTarget(), or until
 *  a parameter it depends on changes. Every setting is a field of
 *  pcl::phaser::PhaserParameters (setParameters()); everything an align() measured is
 * in getResult().
 *
 *  Reference: L. Bernreiter, L. Ott, J. Nieto, R. Siegwart, C. Cadena, "PHASER: a
 * Robust and Correspondence-free Global Pointcloud Registration", IEEE Robotics and
 * Automation Letters 6(2), 2021.
 *
 *  \author the pcl_phaser developers
 *  \ingroup registration
 */
template <typename PointSource, typename PointTarget, typename Scalar = float>
class PhaserRegistration : public Registration<PointSource, PointTarget, Scalar> {
public:
  using Ptr = shared_ptr<PhaserRegistration<PointSource, PointTarget, Scalar>>;
  using ConstPtr =
      shared_ptr<const PhaserRegistration<PointSource, PointTarget, Scalar>>;

  using Base = Registration<PointSource, PointTarget, Scalar>;
  using typename Base::Matrix4;
  using typename Base::PointCloudSource;
  using typename Base::PointCloudSourceConstPtr;
  using typename Base::PointCloudSourcePtr;
  using typename Base::PointCloudTarget;
  using typename Base::PointCloudTargetConstPtr;
  using typename Base::PointCloudTargetPtr;

  using Base::converged_;
  using Base::final_transformation_;
  using Base::getClassName;
  using Base::indices_;
  using Base::input_;
  using Base::reg_name_;
  using Base::target_;
  using Base::transformation_;
  using Base::tree_;

  /** \brief Where the clouds are projected on the sphere
   * (pcl::phaser::ProjectionCenter).
   */
  using ProjectionCenter = pcl::phaser::ProjectionCenter;

  PhaserRegistration()
  {
    reg_name_ = "PhaserRegistration";
    // align() hands each new target to the search tree, which only getFitnessScore()
    // uses: build its index then, not at every align().
    tree_.reset(new pcl::phaser::LazyKdTree<PointTarget>);
  }
  ~PhaserRegistration() override = default;

  /** \brief Provide the source cloud (the one to be aligned). A null or empty cloud is
   *  refused with PCL_ERROR and drops the previous one, so the next align() fails.
   *  \param[in] cloud the source cloud */
  void setInputSource(const PointCloudSourceConstPtr& cloud) override;

  /** \brief Provide the target cloud; drops the cached target. A null or empty cloud is
   *  refused with PCL_ERROR and drops the previous one, so the next align() fails.
   *  \param[in] cloud the target cloud */
  void setInputTarget(const PointCloudTargetConstPtr& cloud) override;

  /** \brief Set every setting at once (pcl::phaser::PhaserParameters, ranges in
   *  pcl::phaser::kParameterRanges). Here and in every setter, a value out of its range
   *  is refused with PCL_ERROR naming it; the previous settings are kept.
   *  \param[in] params the settings */
  void setParameters(const pcl::phaser::PhaserParameters& params)
  {
    setValid(params, "setParameters");
  }
  /** \brief The settings in use. */
  const pcl::phaser::PhaserParameters& getParameters() const { return params_; }

  /** \brief Set the spherical bandwidth B (PhaserParameters::bandwidth, default 64).
   *  \param[in] bandwidth the bandwidth */
  void setBandwidth(int bandwidth)
  {
    pcl::phaser::PhaserParameters params = params_;
    params.bandwidth = bandwidth;
    setValid(params, "setBandwidth");
  }
  /** \brief Get the spherical bandwidth. */
  int getBandwidth() const { return params_.bandwidth; }

  /** \brief Set the number of worker threads (0, the default: one per hardware
   *  thread); results are bit-identical for any count.
   *  \param[in] nr_threads number of threads */
  void setNumberOfThreads(unsigned int nr_threads)
  {
    pcl::phaser::PhaserParameters params = params_;
    params.num_threads = static_cast<int>(nr_threads);
    setValid(params, "setNumberOfThreads");
  }
  /** \brief Get the number of worker threads. */
  unsigned int getNumberOfThreads() const
  {
    return static_cast<unsigned int>(params_.num_threads);
  }

  /** \brief Set where both clouds are projected on the sphere (default SensorOrigin;
   *  getResult().projection_center tells what Automatic chose).
   *  \param[in] center the projection center */
  void setProjectionCenter(ProjectionCenter center)
  {
    params_.projection_center = center;
  }
  /** \brief Get the requested projection center. */
  ProjectionCenter getProjectionCenter() const { return params_.projection_center; }

  /** \brief Fuse the intensity field when both point types have it (default true).
   *  \param[in] use whether to fuse it */
  void setUseIntensity(bool use) { setChannel(phaser::CHANNEL_INTENSITY, use); }
  /** \brief Fuse the reflectivity field (Ouster) when present (default true).
   *  \param[in] use whether to fuse it */
  void setUseReflectivity(bool use) { setChannel(phaser::CHANNEL_REFLECTIVITY, use); }
  /** \brief Fuse the ambient field (Ouster near-IR) when present (default true).
   *  \param[in] use whether to fuse it */
  void setUseAmbient(bool use) { setChannel(phaser::CHANNEL_AMBIENT, use); }
  /** \brief Fuse color (as luminance) when both point types have rgb/rgba (default
   *  true). \param[in] use whether to fuse it */
  void setUseColor(bool use) { setChannel(phaser::CHANNEL_COLOR, use); }
  /** \brief The channels the next align() fuses (pcl::phaser::Channel flags): range
   * plus those both point types carry and that are switched on. */
  std::uint32_t getFusedChannels() const
  {
    return (params_.channels | phaser::CHANNEL_RANGE) &
           phaser::availableChannels<PointSource>() &
           phaser::availableChannels<PointTarget>();
  }

  /** \brief What the last align() found: the transformation, whether it converged,
   *  the center used, the covariance inputs, and in diagnostics its scores,
   *  verification, hypotheses (in the caller's frames) and stage times. */
  const pcl::phaser::PhaserResult& getResult() const { return result_; }

  /** \brief Bingham distribution of the rotation of the last align()
   *  (pcl::phaser::rotationUncertainty); computed on first call. */
  const pcl::phaser::BinghamDistribution& getRotationUncertainty() const;

  /** \brief 6x6 covariance of the pose error of the last align(), ordered (rotation
   *  vector [rad], translation [m]) for omega = Log(R_true R_est^T) and nu = t_true -
   *  t_est (pcl::phaser::poseCovariance): from the final pose's own point-to-plane fit,
   *  calibrated on real revisits; zero unless hasConverged(). */
  Eigen::Matrix<double, 6, 6> getCovariance() const;

  /** \brief Mean squared distance from the transformed source to its nearest target
   *  point, over pairs whose squared distance is <= \a max_range;
   *  `std::numeric_limits<double>::max()` when there is none. Unlike the base class in
   *  PCL 1.13 this skips non-finite source points (Debian's PCL aborts on NaN queries).
   *  The base version is not virtual: a call through a pcl::Registration pointer runs
   *  PCL's.
   *  \param[in] max_range maximum squared distance of a pair that counts */
  double getFitnessScore(double max_range = std::numeric_limits<double>::max());

protected:
  /** \brief Estimate the transformation and transform the whole input into \a output.
   */
  void computeTransformation(PointCloudSource& output, const Matrix4& guess) override;

private:
  void setChannel(phaser::Channel channel, bool use)
  {
    pcl::phaser::PhaserParameters params = params_;
    params.channels = use ? (params.channels | channel) : (params.channels & ~channel);
    setParameters(params);
  }
  /** \brief params_ = \a params when they are valid, else PCL_ERROR from \a setter. */
  void setValid(const pcl::phaser::PhaserParameters& params, const char* setter);

  pcl::phaser::PhaserParameters params_;
  /** \brief The target as the engine keeps it (with its cached spectra); null until the
   *  next align() after setInputTarget() or a change of channels. */
  std::shared_ptr<const pcl::phaser::Target> target_model_;
  pcl::phaser::PhaserResult result_;
  mutable std::shared_ptr<pcl::phaser::BinghamDistribution> rotation_uncertainty_;

public:
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

} // namespace pcl

#ifdef PCL_NO_PRECOMPILE
#include <pcl_phaser/impl/phaser_registration.hpp>
#endif
