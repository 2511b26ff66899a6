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

/** The matches of refinePose's sweep at \a pose (forEachPlaneMatch). */
FitTerms fitTerms(const PointIndex& target, const VerificationSamples& samples,
                  const RigidPose& pose, int num_threads)
{
  FitTerms terms;
  std::vector<Eigen::Vector3d> positions;
  forEachPlaneMatch(
      target, samples, pose,
      [&](const PlaneMatch& m) {
        terms.H += m.weight * m.jacobian * m.jacobian.transpose();
        terms.gradients.push_back(m.weight * m.residual * m.jacobian);
        terms.gradient += terms.gradients.back();
        positions.push_back(m.position);
      },
      num_threads);
  terms.positions.resize(3, static_cast<Eigen::Index>(positions.size()));
  for (std::size_t i = 0; i < positions.size(); ++i)
    terms.positions.col(static_cast<Eigen::Index>(i)) = positions[i];
  return terms;
}

/** M = sum over the blocks of edge \a block of (sum of their g_i)(...)^T, averaged
 *  over the grid and the grid offset by half a block along every axis (a pair of
 *  correlated samples split by one grid's boundary is joined in the other). */
Matrix6d blockMeat(const FitTerms& terms, double block)
{
  Matrix6d M = Matrix6d::Zero();
  for (const double offset : {0.0, 0.5 * block}) {
    const Eigen::Matrix3Xd shifted = terms.positions.array() + offset;
    const VoxelGroups groups = groupByVoxel(shifted, block);
    for (std::size_t g = 0; g < groups.size(); ++g) {
      Vector6d sum = Vector6d::Zero();
      for (Eigen::Index k = groups.offsets[g]; k < groups.offsets[g + 1]; ++k)
        sum += terms.gradients[static_cast<std::size_t>(
            groups.order[static_cast<std::size_t>(k)])];
      M += 0.5 * sum * sum.transpose();
    }
  }
  return M;
}

} // namespace

bool fitCovariance(const PointIndex& target, const VerificationSamples& samples,
                   const RigidPose& pose, double block,
                   Eigen::Matrix<double, 6, 6>& covariance, int num_threads)
{
  if (!(block > 0.0) || samples.weights.size() != samples.points.cols())
    return false;
  const FitTerms terms = fitTerms(target, samples, pose, num_threads);
  if (terms.gradients.size() < static_cast<std::size_t>(kMinFitSamples))
    return false;
  const Eigen::LDLT<Matrix6d> ldlt(terms.H);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() ||
      !(ldlt.vectorD().minCoeff() > 1e-12 * terms.H.trace()))
    return false;
  const Matrix6d Hi = ldlt.solve(Matrix6d::Identity());
  const Vector6d step = -Hi * terms.gradient;
  Matrix6d C = kFitModelErrorFactor * Hi * blockMeat(terms, block) * Hi +
               step * step.transpose();
  C = 0.5 * (C + C.transpose()).eval();
  const double smallest = Eigen::SelfAdjointEigenSolver<Matrix6d>(C).eigenvalues()[0];
  if (!C.allFinite() || !(smallest > 1e-12 * C.trace()))
    return false;
  covariance = C;
  return true;
}

} // namespace pcl::phaser
