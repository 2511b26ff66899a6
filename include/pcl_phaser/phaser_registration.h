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
 *  clouds by spherical and spatial phase correlation (PHASER): the rotation from the
 *  spherical-harmonic spectra correlated on SO(3), the translation from a 3-D FFT
 *  correlation of the voxelized clouds, every hypothesis verified geometrically.
 *  Needs no normals, features or correspondences: a global initializer for
 *  pcl::IterativeClosestPoint:
 *  \code
 *  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
 *  phaser.setInputSource(source);
 *  phaser.setInputTarget(target);
 *  pcl::PointCloud<pcl::PointXYZ> aligned;
 *  phaser.align(aligned);
 *  if (phaser.hasConverged()) // the final pose verified; refine it by ICP
 *    icp.align(aligned, phaser.getFinalTransformation());
 *  \endcode
 *  getFinalTransformation() maps source into target (p_target = T p_source), composed
 *  with the \a guess of align(). Non-finite points are skipped; \a indices_ selects
 *  the source points estimated from; the output is the whole transformed input
 *  (normals rotated). The target's spectra are cached (per parameters) until
 *  setInputTarget(). Settings: pcl::phaser::PhaserParameters; measurements:
 *  getResult().
 *
 *  Reference: L. Bernreiter, L. Ott, J. Nieto, R. Siegwart, C. Cadena, "PHASER: a
 *  Robust and Correspondence-free Global Pointcloud Registration", IEEE Robotics and
 *  Automation Letters 6(2), 2021.
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

  /** \brief Where the clouds are projected on the sphere. */
  using ProjectionCenter = pcl::phaser::ProjectionCenter;

  PhaserRegistration()
  {
    reg_name_ = "PhaserRegistration";
    // Only getFitnessScore() searches the tree: build its index then.
    tree_.reset(new pcl::phaser::LazyKdTree<PointTarget>);
  }
  ~PhaserRegistration() override = default;

  /** \brief Provide the source cloud; a null or empty one fails the next align().
   *  \param[in] cloud the source cloud */
  void setInputSource(const PointCloudSourceConstPtr& cloud) override;

  /** \brief Provide the target cloud; a null or empty one fails the next align().
   *  \param[in] cloud the target cloud */
  void setInputTarget(const PointCloudTargetConstPtr& cloud) override;

  /** \brief Set every setting. Here and in every setter, a value out of its range
   *  (pcl::phaser::kParameterRanges) is refused with PCL_ERROR; nothing changes.
   *  \param[in] params the settings */
  void setParameters(const pcl::phaser::PhaserParameters& params)
  {
    setValid(params, "setParameters");
  }
  /** \brief The settings in use. */
  const pcl::phaser::PhaserParameters& getParameters() const { return params_; }

  /** \brief Set the spherical bandwidth B (default 64). \param[in] bandwidth B */
  void setBandwidth(int bandwidth)
  {
    pcl::phaser::PhaserParameters params = params_;
    params.bandwidth = bandwidth;
    setValid(params, "setBandwidth");
  }
  /** \brief Get the spherical bandwidth. */
  int getBandwidth() const { return params_.bandwidth; }

  /** \brief Set the worker threads (default 0: one per hardware thread).
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

  /** \brief Set where the clouds are projected (default Automatic: about the sensor
   *  origins for scans seen from them, else about the centroids).
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
  /** \brief Fuse color (as luminance) when present (default true).
   *  \param[in] use whether to fuse it */
  void setUseColor(bool use) { setChannel(phaser::CHANNEL_COLOR, use); }
  /** \brief The pcl::phaser::Channel flags the next align() fuses: range plus those
   *  both point types carry and that are switched on. */
  std::uint32_t getFusedChannels() const
  {
    return (params_.channels | phaser::CHANNEL_RANGE) &
           phaser::availableChannels<PointSource>() &
           phaser::availableChannels<PointTarget>();
  }

  /** \brief What the last align() found and measured. */
  const pcl::phaser::PhaserResult& getResult() const { return result_; }

  /** \brief pcl::phaser::rotationUncertainty() of the last align(). */
  const pcl::phaser::BinghamDistribution& getRotationUncertainty() const;

  /** \brief pcl::phaser::poseCovariance() of the last align(); zero unless
   *  hasConverged(). */
  Eigen::Matrix<double, 6, 6> getCovariance() const;

  /** \brief As pcl::Registration's (which is not virtual), but skipping non-finite
   *  source points; `std::numeric_limits<double>::max()` when no pair counts.
   *  \param[in] max_range maximum squared distance of a pair that counts */
  double getFitnessScore(double max_range = std::numeric_limits<double>::max());

protected:
  /** \brief Estimate the transformation; the whole input, moved, into \a output. */
  void computeTransformation(PointCloudSource& output, const Matrix4& guess) override;

private:
  void setChannel(phaser::Channel channel, bool use)
  {
    pcl::phaser::PhaserParameters params = params_;
    params.channels = use ? (params.channels | channel) : (params.channels & ~channel);
    setParameters(params);
  }
  void setValid(const pcl::phaser::PhaserParameters& params, const char* setter);

  pcl::phaser::PhaserParameters params_;
  /// null until the next align() after setInputTarget() or a change of channels
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
