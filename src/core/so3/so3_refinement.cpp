/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "so3/so3_correlation.h"
#include "so3/so3_refinement.h"
#include "support/error.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace pcl::phaser {

namespace {

Eigen::Matrix3d expMap(const Eigen::Vector3d& v)
{
  const double angle = v.norm();
  if (angle == 0.0)
    return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
}

/** The 19-point stencil: 0, +-e_i, +-e_i +- e_k (i < k). */
std::array<Eigen::Vector3d, 19> makeStencil()
{
  std::array<Eigen::Vector3d, 19> s;
  int n = 0;
  s[n++] = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    s[n++] = Eigen::Vector3d::Unit(i);
    s[n++] = -Eigen::Vector3d::Unit(i);
  }
  for (int i = 0; i < 3; ++i)
    for (int k = i + 1; k < 3; ++k)
      for (int si : {1, -1})
        for (int sk : {1, -1})
          s[n++] = si * Eigen::Vector3d::Unit(i) + sk * Eigen::Vector3d::Unit(k);
  return s;
}

/** The objective refineRotation climbs: C and, with supports, C normalized by the
 *  overlap of the observed regions; a rotation whose observed regions do not overlap
 *  scores -inf. */
class RotationObjective {
public:
  RotationObjective(const SphericalSpectrum& target, const SphericalSpectrum& source,
                    const SphericalSupport* target_support,
                    const SphericalSupport* source_support, int num_threads)
      : pairs_{{&target, &source}}
      , num_threads_(num_threads)
  {
    if (target_support) {
      pairs_.push_back({&target_support->energy, &source_support->mask});
      pairs_.push_back({&target_support->mask, &source_support->energy});
    }
  }

  /** \brief The objective at each rotation; \a c_raw receives C there. */
  std::vector<double> operator()(const std::vector<Eigen::Matrix3d>& rotations,
                                 std::vector<double>& c_raw) const
  {
    std::vector<std::vector<double>> v =
        evaluateCorrelations(pairs_, rotations, num_threads_);
    c_raw = v[0];
    if (pairs_.size() == 1)
      return v[0];
    std::vector<double> objective(rotations.size());
    for (std::size_t i = 0; i < rotations.size(); ++i) {
      const double energy = v[1][i] * v[2][i];
      objective[i] = (v[1][i] > 0.0 && v[2][i] > 0.0)
                         ? v[0][i] / std::sqrt(energy)
                         : -std::numeric_limits<double>::infinity();
    }
    return objective;
  }

private:
  std::vector<SpectrumPair> pairs_;
  int num_threads_;
};

/** The step (tangent vector, radians) from the objective \a c on the stencil of
 *  spacing \a h: Newton where the Hessian is negative definite, else \a h along the
 *  gradient; at most \a max_step long, zero when a difference is not finite. */
Eigen::Vector3d newtonStep(const std::vector<double>& c, double h, double max_step)
{
  // Central differences on makeStencil(): 1 + 2i is +e_i, 2 + 2i is -e_i, then blocks
  // of 4 (++, +-, -+, --) for (0,1), (0,2), (1,2).
  Eigen::Vector3d g;
  Eigen::Matrix3d H;
  for (int i = 0; i < 3; ++i) {
    g[i] = (c[1 + 2 * i] - c[2 + 2 * i]) / (2.0 * h);
    H(i, i) = (c[1 + 2 * i] - 2.0 * c[0] + c[2 + 2 * i]) / (h * h);
  }
  int block = 7;
  for (int i = 0; i < 3; ++i)
    for (int k = i + 1; k < 3; ++k, block += 4) {
      H(i, k) = H(k, i) =
          (c[block] - c[block + 1] - c[block + 2] + c[block + 3]) / (4.0 * h * h);
    }
  Eigen::Vector3d delta = Eigen::Vector3d::Zero();
  if (g.allFinite() && H.allFinite()) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(H);
    if (eig.eigenvalues().maxCoeff() < 0.0)
      delta = -H.ldlt().solve(g);
    else if (g.norm() > 0.0)
      delta = h * g / g.norm();
    if (delta.norm() > max_step)
      delta *= max_step / delta.norm();
  }
  return delta;
}

/** \a current, or where the geodesic from \a start to it leaves the trust region of
 *  radius \a max_distance (radians) around \a start. */
Eigen::Matrix3d projectIntoTrustRegion(const Eigen::Matrix3d& start,
                                       const Eigen::Matrix3d& current,
                                       double max_distance)
{
  const Eigen::AngleAxisd away(start.transpose() * current);
  if (away.angle() > max_distance)
    return start * Eigen::AngleAxisd(max_distance, away.axis()).toRotationMatrix();
  return current;
}

} // namespace

RefinedRotation
refineRotation(const SphericalSpectrum& target, const SphericalSpectrum& source,
               const Eigen::Matrix3d& start, int output_bandwidth, int iterations,
               int num_threads, const SphericalSupport* target_support,
               const SphericalSupport* source_support, double max_distance)
{
  if (!(max_distance >= 0.0))
    throw InvalidArgument("refineRotation: max_distance must be >= 0");
  checkBandwidth(output_bandwidth, "output bandwidth");
  if (!target_support != !source_support)
    throw InvalidArgument("refineRotation: give the supports of both signals or none");
  static const std::array<Eigen::Vector3d, 19> stencil = makeStencil();
  const double max_step = M_PI / (2.0 * output_bandwidth);
  double h = max_step;
  const RotationObjective objective(target, source, target_support, source_support,
                                    num_threads);

  RefinedRotation best;
  best.rotation = start;
  best.objective = -std::numeric_limits<double>::infinity();
  best.value = 0.0;
  Eigen::Matrix3d current = start;
  std::vector<Eigen::Matrix3d> rotations(stencil.size());
  std::vector<double> c_raw;
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t i = 0; i < stencil.size(); ++i)
      rotations[i] = current * expMap(h * stencil[i]);
    const std::vector<double> c = objective(rotations, c_raw);
    if (c[0] > best.objective) {
      best.objective = c[0];
      best.value = c_raw[0];
      best.rotation = current;
    }
    current = current * expMap(newtonStep(c, h, max_step));
    current = projectIntoTrustRegion(start, current, max_distance);
    h *= 0.5;
    best.iterations = it + 1;
  }
  const double final_value = objective({current}, c_raw)[0];
  if (final_value >= best.objective) {
    best.objective = final_value;
    best.value = c_raw[0];
    best.rotation = current;
  }
  return best;
}

} // namespace pcl::phaser
