/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include <pcl_phaser/core/error.h>
#include <pcl_phaser/core/so3_correlation.h>
#include <pcl_phaser/core/so3_refinement.h>

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

  std::vector<SpectrumPair> pairs{{&target, &source}};
  if (target_support) {
    pairs.push_back({&target_support->energy, &source_support->mask});
    pairs.push_back({&target_support->mask, &source_support->energy});
  }
  // C and, with supports, the normalized objective at each rotation; a rotation whose
  // observed regions do not overlap scores -inf.
  std::vector<double> c_raw;
  const auto evaluate = [&](const std::vector<Eigen::Matrix3d>& rotations) {
    std::vector<std::vector<double>> v =
        evaluateCorrelations(pairs, rotations, num_threads);
    c_raw = v[0];
    if (pairs.size() == 1)
      return v[0];
    std::vector<double> objective(rotations.size());
    for (std::size_t i = 0; i < rotations.size(); ++i) {
      const double energy = v[1][i] * v[2][i];
      objective[i] = (v[1][i] > 0.0 && v[2][i] > 0.0)
                         ? v[0][i] / std::sqrt(energy)
                         : -std::numeric_limits<double>::infinity();
    }
    return objective;
  };

  RefinedRotation best;
  best.rotation = start;
  best.objective = -std::numeric_limits<double>::infinity();
  best.value = 0.0;
  Eigen::Matrix3d current = start;
  std::vector<Eigen::Matrix3d> rotations(stencil.size());
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t i = 0; i < stencil.size(); ++i)
      rotations[i] = current * expMap(h * stencil[i]);
    const std::vector<double> c = evaluate(rotations);
    if (c[0] > best.objective) {
      best.objective = c[0];
      best.value = c_raw[0];
      best.rotation = current;
    }
    // Central differences; indices follow makeStencil(): 1 + 2i is +e_i, 2 + 2i is
    // -e_i, and the mixed terms come in blocks of 4 (++, +-, -+, --) for (0,1), (0,2),
    // (1,2).
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
    current = current * expMap(delta);
    // Inside the trust region around the start: project a step that leaves it onto its
    // boundary (along the geodesic from the start).
    const Eigen::AngleAxisd away(start.transpose() * current);
    if (away.angle() > max_distance)
      current = start * Eigen::AngleAxisd(max_distance, away.axis()).toRotationMatrix();
    h *= 0.5;
    best.iterations = it + 1;
  }
  const double final_value = evaluate({current})[0];
  if (final_value >= best.objective) {
    best.objective = final_value;
    best.value = c_raw[0];
    best.rotation = current;
  }
  return best;
}

} // namespace pcl::phaser
