/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The covariance of a pose from the point-to-plane fit of its verification samples:
 * a cluster-robust sandwich over blocks of correlated samples, with a model-error
 * factor (pose_covariance.h).
 */
#include "uncertainty/pose_covariance.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <vector>

namespace pcl::phaser {

namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/** The fit's terms at a pose: per matched sample its moved position and g_i = w_i r_i
 *  J_i, and the normal matrix H = sum w J J^T. */
struct FitTerms {
  Eigen::Matrix3Xd positions; ///< 3 x m, the moved samples that matched
  std::vector<Vector6d> gradients;
  Matrix6d H = Matrix6d::Zero();
  Vector6d gradient = Vector6d::Zero(); ///< sum of the g_i
};

/** The matches of refinePose's sweep at \a pose (same nearest point, normal test and
 *  weight w = sample weight x (1 - d^2 / r^2)^2). */
FitTerms fitTerms(const PointIndex& target, const VerificationSamples& s,
                  const RigidPose& pose)
{
  const bool with_normals = s.normals.cols() == s.points.cols();
  const double r2 = target.radius() * target.radius();
  FitTerms f;
  std::vector<Eigen::Vector3d> positions;
  for (Eigen::Index i = 0; i < s.points.cols(); ++i) {
    const Eigen::Vector3d q = pose.R * s.points.col(i) + pose.t;
    const Eigen::Vector3d n_s = with_normals
                                    ? Eigen::Vector3d(pose.R * s.normals.col(i))
                                    : Eigen::Vector3d::Zero();
    const Eigen::Index k = target.nearest(q, n_s, kMinNormalCosine);
    if (k < 0 || target.normal(k).isZero())
      continue;
    const Eigen::Vector3d n = target.normal(k);
    const Eigen::Vector3d d = q - target.point(k);
    const double closeness = 1.0 - d.squaredNorm() / r2;
    const double w = s.weights[i] * closeness * closeness;
    Vector6d J;
    J << q.cross(n), n;
    f.H += w * J * J.transpose();
    f.gradients.push_back(w * n.dot(d) * J);
    f.gradient += f.gradients.back();
    positions.push_back(q);
  }
  f.positions.resize(3, static_cast<Eigen::Index>(positions.size()));
  for (std::size_t i = 0; i < positions.size(); ++i)
    f.positions.col(static_cast<Eigen::Index>(i)) = positions[i];
  return f;
}

/** M = sum over the blocks of edge \a block of (sum of their g_i)(...)^T, averaged
 *  over the grid and the grid offset by half a block along every axis (a pair of
 *  correlated samples split by one grid's boundary is joined in the other). */
Matrix6d blockMeat(const FitTerms& f, double block)
{
  Matrix6d M = Matrix6d::Zero();
  for (const double offset : {0.0, 0.5 * block}) {
    const Eigen::Matrix3Xd shifted = f.positions.array() + offset;
    const VoxelGroups groups = groupByVoxel(shifted, block);
    for (std::size_t g = 0; g < groups.size(); ++g) {
      Vector6d sum = Vector6d::Zero();
      for (Eigen::Index k = groups.offsets[g]; k < groups.offsets[g + 1]; ++k)
        sum += f.gradients[static_cast<std::size_t>(
            groups.order[static_cast<std::size_t>(k)])];
      M += 0.5 * sum * sum.transpose();
    }
  }
  return M;
}

} // namespace

bool fitCovariance(const PointIndex& target, const VerificationSamples& samples,
                   const RigidPose& pose, double block,
                   Eigen::Matrix<double, 6, 6>& covariance)
{
  if (!(block > 0.0) || samples.weights.size() != samples.points.cols())
    return false;
  const FitTerms f = fitTerms(target, samples, pose);
  if (f.gradients.size() < static_cast<std::size_t>(kMinFitSamples))
    return false;
  const Eigen::LDLT<Matrix6d> ldlt(f.H);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() ||
      !(ldlt.vectorD().minCoeff() > 1e-12 * f.H.trace()))
    return false;
  const Matrix6d Hi = ldlt.solve(Matrix6d::Identity());
  const Vector6d step = -Hi * f.gradient;
  Matrix6d C =
      kFitModelErrorFactor * Hi * blockMeat(f, block) * Hi + step * step.transpose();
  C = 0.5 * (C + C.transpose()).eval();
  const double smallest = Eigen::SelfAdjointEigenSolver<Matrix6d>(C).eigenvalues()[0];
  if (!C.allFinite() || !(smallest > 1e-12 * C.trace()))
    return false;
  covariance = C;
  return true;
}

} // namespace pcl::phaser
