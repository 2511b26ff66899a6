/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/core/bingham.h>
#include <pcl_phaser/core/pipeline.h>
#include <pcl_phaser/core/projection_centre.h>
#include <pcl_phaser/point_channels.h>

#include <pcl/registration/registration.h>

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace pcl {

/** \brief PhaserRegistration: correspondence-free global registration of two point
 * clouds by spherical and spatial phase correlation (PHASER).
 *
 *  \details The rotation comes from correlating the spherical-harmonic spectra of the
 * two clouds, projected on the sphere about a centre, on SO(3) (Kostelec-Rockmore),
 * beside the correlation of their surface-orientation histograms, refined by Newton
 * steps with exact evaluation; the translation from a whitened 3-D FFT correlation of
 * the voxelised target and rotated source, with a sub-voxel peak. Every hypothesis is
 * verified geometrically and the best one wins. About sensor origins hasConverged()
 * means the final pose verified (pcl_phaser::PhaserEstimate::verified: enough source
 * samples on the target with agreeing normals, few in space the target saw through,
 * and a match that pins the translation down in every direction); about centroids it
 * also needs a distinct correlation peak (setMinimumPeakScore()). No normals, features
 * or correspondences are needed as input, so it replaces
 * pcl::SampleConsensusInitialAlignment as the global initialiser ahead of
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
 *  (p_target = T p_source), as for every pcl::Registration. A \a guess passed to
 * align() is applied to the source first and the estimate is composed with it.
 * Non-finite points are skipped; \a indices_ selects the source points used for the
 * estimate, while the output is the whole transformed input (PCL's convention), with
 * normals rotated for point types that carry them. Everything that depends only on the
 * target (its spherical spectrum and voxel spectrum) is cached until setInputTarget()
 * or a parameter change.
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

  /** \brief Where the clouds are projected on the sphere. */
  enum class ProjectionCenter {
    SensorOrigin, ///< the origin of each cloud's frame (LiDAR scans in their sensor
                  ///< frame)
    Centroid, ///< each cloud's centroid (object scans, clouds far from their origin)
    Automatic ///< SensorOrigin when both clouds look like spinning-LiDAR scans in their
              ///< sensor frame (pcl_phaser::looksSensorCentred: they surround their
              ///< origin in a band with empty poles), else Centroid; see
              ///< getUsedProjectionCenter()
  };

  PhaserRegistration() { reg_name_ = "PhaserRegistration"; }
  ~PhaserRegistration() override = default;

  /** \brief Provide the source cloud (the one to be aligned); drops per-source state.
   */
  void setInputSource(const PointCloudSourceConstPtr& cloud) override;

  /** \brief Provide the target cloud; invalidates the cached target spectra. */
  void setInputTarget(const PointCloudTargetConstPtr& cloud) override;

  /** \brief Set all engine parameters at once (see pcl_phaser::PhaserParameters for
   *  each field's meaning, range and default); they are validated at align().
   *  Invalidates the cached target. \param[in] params the parameters */
  void setParameters(const pcl_phaser::PhaserParameters& params)
  {
    params_ = params;
    invalidateTarget();
  }

  /** \brief The engine parameters in use. */
  const pcl_phaser::PhaserParameters& getParameters() const { return params_; }

  /** \brief Set the spherical bandwidth B (1..256): the sphere is sampled on a 2B x 2B
   * grid and the SO(3) grid spacing is pi/B (before refinement). Default 64. \param[in]
   * bandwidth the bandwidth */
  void setBandwidth(int bandwidth)
  {
    params_.bandwidth = bandwidth;
    invalidateTarget();
  }
  /** \brief Get the spherical bandwidth. */
  int getBandwidth() const { return params_.bandwidth; }

  /** \brief Set the number of voxels along the longest axis of the translation grid
   *  (8..1024); the grid is sized to the target with a margin. Default 128.
   *  \param[in] grid_size voxels along the longest axis */
  void setSpatialGridSize(int grid_size)
  {
    params_.spatial_grid_size = grid_size;
    invalidateTarget();
  }
  /** \brief Get the number of voxels along the longest axis of the translation grid. */
  int getSpatialGridSize() const { return params_.spatial_grid_size; }

  /** \brief Set an explicit voxel size in metres for the translation grid; 0 (default)
   *  derives it from the spatial grid size and the extent of the target.
   *  \param[in] voxel_size voxel edge length in metres (>= 0) */
  void setVoxelSize(double voxel_size)
  {
    params_.voxel_size = voxel_size;
    invalidateTarget();
  }
  /** \brief Get the explicit voxel size (0 when derived from the grid size). */
  double getVoxelSize() const { return params_.voxel_size; }

  /** \brief Set the number of Newton iterations that refine the rotation peak (0..10),
   *  on plain correlation and again on the normalised one (setNormalizedRefinement).
   *  Default 2: a third changed the simulated demo pairs' errors by < 0.01 deg.
   *  \param[in] iterations number of iterations */
  void setRefinementIterations(int iterations)
  {
    params_.refinement_iterations = iterations;
  }
  /** \brief Get the number of Newton iterations of the rotation refinement. */
  int getRefinementIterations() const { return params_.refinement_iterations; }

  /** \brief Set the number of passes (1..5). Pass 1 estimates rotation and translation
   *  with each cloud projected about its own centre; every further pass projects the
   *  source, moved by the current estimate, about the target's centre, so the range
   *  function no longer suffers the parallax of the source's viewpoint, and measures
   * the residual shift on a fine grid over the target's inner region. This is a
   *  maximum: the passes stop once a shift update is below a quarter of a fine voxel.
   *  Default 3.
   *  \param[in] passes number of passes */
  void setNumberOfPasses(int passes)
  {
    params_.passes = passes;
    invalidateTarget();
  }
  /** \brief Get the number of passes. */
  int getNumberOfPasses() const { return params_.passes; }

  /** \brief Refine the rotation further on the energy-normalised SO(3) correlation,
   *  within 0.75 deg x 64 / B of the maximum of the plain one, when the clouds are
   *  projected about their sensor origins (default true). Plain correlation leans
   *  towards equal sensor tilt when two scanners are rolled or pitched against each
   *  other (their field-of-view bands overlap best at equal tilt: 1.2-1.4 deg on the
   *  simulated demo pairs); the normalised one removes most of that (0.5-0.6 deg left)
   *  for about 8 ms more per align with 2 threads (doc/benchmarks.md sections 2, 6).
   *  About the centroid (object scans) there is no such band: the plain refinement is
   *  kept there.
   *  \param[in] normalized whether to normalise */
  void setNormalizedRefinement(bool normalized)
  {
    params_.normalized_refinement = normalized;
    invalidateTarget();
  }
  /** \brief Whether the rotation is refined on the energy-normalised correlation. */
  bool getNormalizedRefinement() const { return params_.normalized_refinement; }

  /** \brief Fuse the intensity field, when the point type has one (default true).
   *  \param[in] use whether to fuse it */
  void setUseIntensity(bool use) { setChannel(phaser::CHANNEL_INTENSITY, use); }
  /** \brief Whether the intensity field is fused when present. */
  bool getUseIntensity() const { return channel_mask_ & phaser::CHANNEL_INTENSITY; }
  /** \brief Fuse the reflectivity field (Ouster), when present (default true).
   *  \param[in] use whether to fuse it */
  void setUseReflectivity(bool use) { setChannel(phaser::CHANNEL_REFLECTIVITY, use); }
  /** \brief Whether the reflectivity field is fused when present. */
  bool getUseReflectivity() const
  {
    return channel_mask_ & phaser::CHANNEL_REFLECTIVITY;
  }
  /** \brief Fuse the ambient field (Ouster near-IR), when present (default true).
   *  \param[in] use whether to fuse it */
  void setUseAmbient(bool use) { setChannel(phaser::CHANNEL_AMBIENT, use); }
  /** \brief Whether the ambient field is fused when present. */
  bool getUseAmbient() const { return channel_mask_ & phaser::CHANNEL_AMBIENT; }
  /** \brief Fuse colour (as luminance), when the point type has rgb/rgba (default
   * true). \param[in] use whether to fuse it */
  void setUseColor(bool use) { setChannel(phaser::CHANNEL_COLOR, use); }
  /** \brief Whether colour is fused when present. */
  bool getUseColor() const { return channel_mask_ & phaser::CHANNEL_COLOR; }
  /** \brief The channels the next align() fuses: range plus those both point types have
   *  and that are switched on (phaser::Channel flags). */
  std::uint32_t getFusedChannels() const { return fusedChannels(); }

  /** \brief Set the number of Laplacian pyramid levels of the channel fusion (1..8; 1
   * is a plain average). Default 5. \param[in] levels number of levels */
  void setFusionLevels(int levels)
  {
    params_.fusion_levels = levels;
    invalidateTarget();
  }
  /** \brief Get the number of pyramid levels of the channel fusion. */
  int getFusionLevels() const { return params_.fusion_levels; }

  /** \brief Set the number of worker threads (0..64); results are bit-identical for any
   *  count. Default 0: one per hardware thread (PCL's convention).
   *  \param[in] nr_threads number of threads, 0 for automatic */
  void setNumberOfThreads(unsigned int nr_threads)
  {
    params_.num_threads = static_cast<int>(nr_threads);
  }
  /** \brief Get the number of worker threads. */
  unsigned int getNumberOfThreads() const
  {
    return static_cast<unsigned int>(params_.num_threads);
  }

  /** \brief Set the centre of the spherical projection. Default SensorOrigin.
   *  \param[in] center where both clouds are projected on the sphere */
  void setProjectionCenter(ProjectionCenter center)
  {
    center_ = center;
    invalidateTarget();
  }
  /** \brief Get the centre of the spherical projection. */
  ProjectionCenter getProjectionCenter() const { return center_; }

  /** \brief The centre the last align() used: getProjectionCenter(), or with Automatic
   *  what it chose (SensorOrigin or Centroid). */
  ProjectionCenter getUsedProjectionCenter() const { return used_center_; }

  /** \brief Set the translation peak score (peak-to-sidelobe ratio of the Laplacian
   *  of the final 3-D correlation) above which hasConverged() is true about centroids
   *  (about sensor origins the verification decides alone). Default 20:
   *  identical scans score 56-132 and registrations of unrelated scenes at most 19.
   *  Half of it suffices when the aligned clouds also overlap well
   *  (getNormalizedOverlap() >= getMinimumNormalizedOverlap()); see doc/benchmarks.md
   *  section 5.
   *  \param[in] score the threshold (>= 0) */
  void setMinimumPeakScore(double score) { min_peak_score_ = score; }
  /** \brief Get the smallest translation peak score that counts as converged. */
  double getMinimumPeakScore() const { return min_peak_score_; }

  /** \brief Set the normalised overlap (getNormalizedOverlap()) from which a peak
   *  score of half the minimum suffices for hasConverged(). Default 0.55: correct
   *  registrations of scans from viewpoints metres apart overlap 0.59-0.83 but their
   *  peak score can fall to 12 (the peak is wider than that of a scan against itself),
   *  while wrong registrations on the shared scans overlapped at most 0.47.
   *  \param[in] overlap the threshold, in [0, 1] */
  void setMinimumNormalizedOverlap(double overlap)
  {
    min_normalized_overlap_ = overlap;
  }
  /** \brief Get the normalised overlap from which half the peak score suffices. */
  double getMinimumNormalizedOverlap() const { return min_normalized_overlap_; }

  /** \brief Cosine similarity of the aligned voxel grids (peak of the final 3-D
   *  correlation over the norms of the two grids), in [-1, 1]. */
  double getNormalizedOverlap() const { return estimate_.normalized_overlap; }

  /** \brief Normalised SO(3) correlation at the estimated rotation, in [-1, 1]. */
  double getRotationScore() const { return estimate_.rotation_score; }

  /** \brief Quality of the translation peak (see pcl_phaser::PhaserEstimate). */
  double getTranslationScore() const { return estimate_.translation_score; }

  /** \brief Set how many distinct rotation peaks of the first global search are taken
   *  through the translation stage (1..10); the one whose rotated source overlaps the
   *  target most wins. More than one matters for scenes with symmetries (corridors,
   *  tunnels, symmetric rooms). Default 3.
   *  \param[in] nr_candidates number of rotation hypotheses */
  void setNumberOfRotationCandidates(int nr_candidates)
  {
    params_.rotation_candidates = nr_candidates;
  }
  /** \brief Get the number of rotation hypotheses of the first global search. */
  int getNumberOfRotationCandidates() const { return params_.rotation_candidates; }

  /** \brief A hypothesis of the first global search, in the caller's frames. */
  struct Candidate {
    Matrix4 transformation;      ///< maps the source into the target frame
    double rotation_score = 0.0; ///< normalised SO(3) correlation at its grid peak
    double overlap = 0.0;        ///< peak of its 3-D correlation (larger is better)
    bool chosen = false;         ///< the one the final estimate was refined from
    PCL_MAKE_ALIGNED_OPERATOR_NEW
  };

  /** \brief The hypotheses of the last align(), in the order of their rotation peaks.
   */
  const std::vector<Candidate, Eigen::aligned_allocator<Candidate>>&
  getCandidates() const
  {
    return candidates_;
  }

  /** \brief Covariance of the translation in metres^2 (target frame): the error of
   *  the sub-voxel peak of the final 3-D correlation under the noise its sidelobes
   * show, scaled by how much the two clouds differ (pcl_phaser::translationCovariance).
   * It is not the width of the peak (paper eq. 15), which is far wider than the error.
   */
  Eigen::Matrix3d getTranslationCovariance() const
  {
    return estimate_.translation_covariance;
  }

  /** \brief Bingham distribution of the rotation (orientation M, concentrations Z, mode
   *  = the estimate), fitted by maximum likelihood to the grid rotations around the
   * last SO(3) correlation peak weighted by their correlation (paper eqs. 6, 7, 11,
   * 12). Quaternions are (w, x, y, z); the spread is expressed in the target frame.
   * Computed on first call after align(). */
  const pcl_phaser::BinghamDistribution& getRotationUncertainty() const;

  /** \brief 6x6 covariance of the pose error, ordered (rotation vector [rad],
   * translation [m]) for omega = Log(R_true R_est^T) and nu = t_true - t_est, so its
   * inverse can serve as the information matrix of a pose-graph edge. The rotation
   * block is the Bingham's tangent covariance plus a model error (0.11 pi / B)^2 per
   * axis (pcl_phaser::rotationCovariance); the translation block adds to
   * getTranslationCovariance() the effect of the rotation error on the translation
   * through the lever arm of the source centre. Symmetric positive definite when
   * hasConverged(); zero otherwise. Calibration: doc/benchmarks.md section 5. */
  Eigen::Matrix<double, 6, 6> getCovariance() const;

  /** \brief Everything the last align() measured: scores and the time of each stage. */
  const pcl_phaser::PhaserEstimate& getEstimate() const { return estimate_; }

  /** \brief Mean squared distance from the transformed source to its nearest target
   *  point, over pairs whose squared distance is <= \a max_range;
   *  `std::numeric_limits<double>::max()` when there is none. Unlike the base class in
   *  PCL 1.13 this skips non-finite source points (Debian's PCL aborts on NaN queries).
   *  Note that the base version is not virtual: a call through a pcl::Registration
   *  pointer runs PCL's.
   *  \param[in] max_range maximum squared distance of a pair that counts */
  double getFitnessScore(double max_range = std::numeric_limits<double>::max());

protected:
  /** \brief Estimate the transformation and transform the whole input into \a output.
   */
  void computeTransformation(PointCloudSource& output, const Matrix4& guess) override;

private:
  void invalidateTarget()
  {
    target_model_.reset();
    target_sensor_centred_ = -1;
  }

  /** \brief The finite target points and their channels; false (with \a problem) when
   *  there are none or they are too far out. */
  bool extractTarget(Eigen::Matrix3Xd& points, pcl_phaser::ChannelValues& channels,
                     std::string& problem) const;

  void setChannel(phaser::Channel channel, bool use)
  {
    channel_mask_ = use ? (channel_mask_ | channel) : (channel_mask_ & ~channel);
    invalidateTarget();
  }

  std::uint32_t fusedChannels() const
  {
    return channel_mask_ & phaser::availableChannels<PointSource>() &
           phaser::availableChannels<PointTarget>();
  }

  /** \brief Fails with PCL_ERROR, final transformation = guess, not converged. */
  void fail(PointCloudSource& output, const Matrix4& guess, const std::string& reason);

  pcl_phaser::PhaserParameters params_;
  ProjectionCenter center_ = ProjectionCenter::SensorOrigin;
  std::uint32_t channel_mask_ = ~0u;
  double min_peak_score_ = 20.0;
  double min_normalized_overlap_ = 0.55;
  std::shared_ptr<const pcl_phaser::TargetModel> target_model_;
  ProjectionCenter model_center_ = ProjectionCenter::SensorOrigin; ///< of target_model_
  ProjectionCenter used_center_ = ProjectionCenter::SensorOrigin;
  double target_sensor_centred_ = -1; ///< viewCoverage of the target; < 0: not computed
  Eigen::Vector3d target_center_ = Eigen::Vector3d::Zero();
  pcl_phaser::PhaserEstimate estimate_;
  std::vector<Candidate, Eigen::aligned_allocator<Candidate>> candidates_;
  /** \brief R c_s of the last align(): how far the rotation error moves the
   * translation. */
  Eigen::Vector3d lever_arm_ = Eigen::Vector3d::Zero();
  mutable std::shared_ptr<pcl_phaser::BinghamDistribution> rotation_uncertainty_;

public:
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

} // namespace pcl

#ifdef PCL_NO_PRECOMPILE
#include <pcl_phaser/impl/phaser_registration.hpp>
#endif
