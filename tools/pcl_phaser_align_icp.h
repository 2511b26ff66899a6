// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file pcl_phaser_align_icp.h
 * \brief The ICP refinement of `pcl_phaser_align -icp`: both clouds thinned on a voxel
 * grid, the correspondence distance bounded by the global result's covariance, and
 * PCL's point-to-plane (or point-to-point) ICP from the global pose. Its settings are
 * here; the refinement itself (icp_refinement.h) runs in a module the tool opens when
 * -icp is given (pcl_phaser_align_icp.cpp), as only it needs libpcl_features (42 MB),
 * whose dynamic linking cost every run about 0.1 s.
 */
#pragma once

#include "pcl_phaser_align_steps.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace pcl {
namespace phaser {
namespace align_tool {

const int icp_iterations = 50;
// ICP stops when an iteration moves the pose by < 1 mm and turns it by < 0.026 deg
// (1 - cos = 1e-7): 4-6 iterations on KITTI and the revisits, where 0.1 mm / 0.008 deg
// took 5-9 for the same errors.
const double icp_transformation_epsilon = 1e-6; // m^2
const double icp_rotation_epsilon = 1e-7;       // 1 - cos
const int icp_normal_neighbors = 15;
// ICP runs on the target reduced to one point per voxel of a quarter of --icp-dist
// (0.25 m by default) and the source to half of it (0.5 m): ICP / global time on KITTI
// 0.78 -> 0.38, on 9 revisits 0.37-3.85 -> 0.15-0.24 (both clouds at 0.25 m before).
const double icp_voxel_fraction = 0.25;
const double icp_source_voxel_fraction = 0.5;
// The correspondence distance: 3 standard deviations of the global pose
// (pcl::PhaserRegistration::getCovariance()) at the 90 % quantile of the source's
// range, at least one target voxel, at most --icp-dist. With the fixed 1 m of before,
// ICP drifted on the revisits 11.8-20.8 m apart (0.50-1.06 deg after ICP, PHASER
// 0.17-0.49); the bound gives 0.07-0.30 deg there (it sits at the floor on 9 of 11
// pairs, 0.31-0.35 m on the others).
const double icp_distance_sigmas = 3.0;
const double icp_extent_quantile = 0.9;
const double icp_distance_floor_voxels = 1.0;

/** \brief How refine() runs ICP. */
struct IcpSettings {
  double max_distance = 1.0; ///< max correspondence distance, meters
  int iterations = 50;       ///< maximum number of iterations
  /** \brief Converged when an iteration moves the pose by less than the square root
   *  of this (m^2) and rotates it by less than rotation_epsilon. */
  double transformation_epsilon = 1e-8;
  /** \brief 1 - cos of the rotation step that counts as converged; 0: PCL's default
   *  (1 - transformation_epsilon). */
  double rotation_epsilon = 0.0;
  int normal_neighbors = 15;   ///< k of the target's normals (point-to-plane)
  bool point_to_point = false; ///< plain pcl::IterativeClosestPoint
  unsigned threads = 1;        ///< threads of the normal estimation
  /** \brief Edge (meters) of the pcl::VoxelGrid that the target is reduced to before
   *  ICP (one centroid per occupied voxel); 0: the full cloud. */
  double voxel_size = 0.0;
  /** \brief The same for the source (the cost of an iteration grows with it; the
   *  target's voxels set how well its planes are sampled); 0: the full cloud. */
  double source_voxel_size = 0.0;
};

/** \brief What refine() ran on (for the report; zero before it ran). */
struct IcpRun {
  std::size_t source_points = 0, target_points = 0; ///< after thinning (and normals)
  int iterations = 0;                               ///< ICP iterations run
};

/** \brief The \a quantile (0..1) of the distances of \a cloud's points from its
 *  origin (the sensor, for a scan), meters; 0 for an empty cloud. The lever of a
 *  rotation error: a point at distance r moves by about r times the angle. */
template <typename PointT>
double cloudExtent(const pcl::PointCloud<PointT>& cloud, double quantile)
{
  if (cloud.empty())
    return (0.0);
  std::vector<float> range;
  range.reserve(cloud.size());
  for (const PointT& p : cloud)
    range.push_back(p.getVector3fMap().norm());
  const double q = std::min(1.0, std::max(0.0, quantile));
  const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(range.size() - 1));
  std::nth_element(range.begin(), range.begin() + k, range.end());
  return (static_cast<double>(range[static_cast<std::size_t>(k)]));
}

/** \brief A correspondence distance for ICP from the global pose's covariance
 *  (pcl::PhaserRegistration::getCovariance(): rotation vector [rad], then translation
 *  [m]): \a sigmas times (the translation's largest standard deviation plus the
 *  rotation's largest one times \a extent), which bounds \a sigmas standard deviations
 *  of the displacement of a point at distance \a extent from the source origin,
 *  clamped to [\a floor, \a cap]. \a cap when the covariance is not finite or has a
 *  negative or zero diagonal (nothing known: the user's distance).
 *  \param[in] covariance 6 x 6 covariance of the global pose error
 *  \param[in] extent lever of the rotation error, meters (cloudExtent())
 *  \param[in] sigmas how many standard deviations the bound covers
 *  \param[in] floor,cap the smallest and largest distance returned, meters */
inline double correspondenceDistance(const Eigen::Matrix<double, 6, 6>& covariance,
                                     double extent, double sigmas, double floor,
                                     double cap)
{
  if (!covariance.allFinite() || !(covariance.diagonal().minCoeff() > 0.0) ||
      !std::isfinite(extent))
    return (cap);
  const auto largestSigma = [](const Eigen::Matrix3d& block) {
    const Eigen::Matrix3d sym = 0.5 * (block + block.transpose());
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(sym,
                                                             Eigen::EigenvaluesOnly);
    return (std::sqrt(std::max(0.0, eig.eigenvalues().maxCoeff())));
  };
  const double rotation = largestSigma(covariance.topLeftCorner<3, 3>());
  const double translation = largestSigma(covariance.bottomRightCorner<3, 3>());
  const double bound = sigmas * (translation + rotation * std::max(0.0, extent));
  return (std::min(cap, std::max(floor, bound)));
}

/** \brief The settings of `pcl_phaser_align -icp`: the constants above, the clouds
 *  thinned to fractions of \a cap, and the correspondence distance from the global
 *  pose's \a covariance by correspondenceDistance() with the lever cloudExtent() of
 *  \a source, within [one target voxel, \a cap].
 *  \param[in] cap the largest correspondence distance, meters (--icp-dist)
 *  \param[in] point_to_point plain point-to-point ICP (--icp-point)
 *  \param[in] covariance pcl::PhaserRegistration::getCovariance() of the guess
 *  \param[in] source the full source cloud */
template <typename PointT>
IcpSettings toolIcpSettings(double cap, bool point_to_point,
                            const Eigen::Matrix<double, 6, 6>& covariance,
                            const pcl::PointCloud<PointT>& source)
{
  IcpSettings icp;
  icp.iterations = icp_iterations;
  icp.transformation_epsilon = icp_transformation_epsilon;
  icp.rotation_epsilon = icp_rotation_epsilon;
  icp.normal_neighbors = icp_normal_neighbors;
  icp.point_to_point = point_to_point;
  icp.voxel_size = icp_voxel_fraction * cap;
  icp.source_voxel_size = icp_source_voxel_fraction * cap;
  icp.max_distance = correspondenceDistance(
      covariance, cloudExtent(source, icp_extent_quantile), icp_distance_sigmas,
      icp_distance_floor_voxels * icp.voxel_size, cap);
  return (icp);
}

/** \brief refine() (icp_refinement.h) in the ICP module, for PointXYZ and PointXYZI.
 * \param[in] source,target finite clouds
 * \param[in] guess the initial T_target_source
 * \param[in] settings ICP parameters
 * \param[out] s transform, converged, time_ms and ran
 * \param[out] run the points and iterations used
 * \param[out] error why not, when false is returned (the module cannot be loaded)
 * \return true when ICP ran */
template <typename PointT>
bool refineInModule(const typename pcl::PointCloud<PointT>::Ptr& source,
                    const typename pcl::PointCloud<PointT>::Ptr& target,
                    const Eigen::Matrix4d& guess, const IcpSettings& settings, Stage& s,
                    IcpRun& run, std::string& error);

} // namespace align_tool
} // namespace phaser
} // namespace pcl
