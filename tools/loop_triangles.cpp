/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "loop_triangles.h"
#include "statistics.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <utility>

namespace pcl {
namespace phaser {
namespace batch {

namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct Measured {
  Eigen::Matrix4d T;
  Matrix6d C;
};

Eigen::Matrix3d skew(const Eigen::Vector3d& v)
{
  return (Eigen::Matrix3d() << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0)
      .finished();
}

Eigen::Vector3d logSo3(const Eigen::Matrix3d& R)
{
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

/** x^T S^-1 x, or infinity when S is not positive definite. */
template <int N>
double mahalanobis(const Eigen::Matrix<double, N, 1>& x,
                   const Eigen::Matrix<double, N, N>& S)
{
  const Eigen::LLT<Eigen::Matrix<double, N, N>> llt(S);
  if (llt.info() != Eigen::Success)
    return std::numeric_limits<double>::infinity();
  return x.dot(llt.solve(x));
}

Closure close(int a, int b, int c, const Measured& ab, const Measured& bc,
              const Measured& ac)
{
  const Eigen::Matrix3d Rab = ab.T.topLeftCorner<3, 3>(),
                        Rbc = bc.T.topLeftCorner<3, 3>(),
                        Rac = ac.T.topLeftCorner<3, 3>();
  const Eigen::Vector3d tab = ab.T.topRightCorner<3, 1>(),
                        tbc = bc.T.topRightCorner<3, 1>(),
                        tac = ac.T.topRightCorner<3, 1>();
  Closure out{a, b, c};
  out.residual << logSo3(Rab * Rbc * Rac.transpose()), Rab * tbc + tab - tac;
  // First order: d r / d delta_ab = [I 0; -[R_ab t_bc]x I], d r / d delta_bc =
  // diag(R_ab, R_ab), d r / d delta_ac = -I.
  Matrix6d J1 = Matrix6d::Identity(), J2 = Matrix6d::Zero();
  J1.bottomLeftCorner<3, 3>() = -skew(Rab * tbc);
  J2.topLeftCorner<3, 3>() = Rab;
  J2.bottomRightCorner<3, 3>() = Rab;
  const Matrix6d S = J1 * ab.C * J1.transpose() + J2 * bc.C * J2.transpose() + ac.C;
  out.nees = mahalanobis<6>(out.residual, S);
  out.nees_rotation =
      mahalanobis<3>(out.residual.head<3>(), Eigen::Matrix3d(S.topLeftCorner<3, 3>()));
  out.nees_translation = mahalanobis<3>(out.residual.tail<3>(),
                                        Eigen::Matrix3d(S.bottomRightCorner<3, 3>()));
  return out;
}

} // namespace

std::vector<Closure> loopClosures(const std::vector<Record>& records)
{
  std::map<std::pair<int, int>, Measured> edges;
  for (const Record& r : records) {
    Measured m;
    if (!convergedEdge(r, m.T, m.C))
      continue;
    const int i = r["target_id"].get<int>(), j = r["source_id"].get<int>();
    if (i < j)
      edges[{i, j}] = m;
    else if (i > j) { // the later scan as target: the inverse edge
      // Of T^-1 = (R^T, -R^T t), to first order: omega' = -R^T omega and
      // nu' = -R^T nu - R^T [t]x omega, in the frame of scan j.
      const Eigen::Matrix3d Rt = m.T.topLeftCorner<3, 3>().transpose();
      Matrix6d J = Matrix6d::Zero();
      J.topLeftCorner<3, 3>() = -Rt;
      J.bottomRightCorner<3, 3>() = -Rt;
      J.bottomLeftCorner<3, 3>() = -Rt * skew(m.T.topRightCorner<3, 1>());
      edges[{j, i}] = {m.T.inverse(), J * m.C * J.transpose()};
    }
  }
  std::vector<Closure> out;
  for (const auto& [ab, e_ab] : edges)
    for (auto it = edges.lower_bound({ab.second, ab.second + 1});
         it != edges.end() && it->first.first == ab.second; ++it) {
      const auto ac = edges.find({ab.first, it->first.second});
      if (ac != edges.end())
        out.push_back(
            close(ab.first, ab.second, it->first.second, e_ab, it->second, ac->second));
    }
  return out;
}

std::string closureSummary(const std::vector<Closure>& closures)
{
  if (closures.empty())
    return "no triangle of converged edges";
  std::size_t within = 0, within_r = 0, within_t = 0;
  double sum = 0.0;
  std::vector<double> angles, distances;
  for (const Closure& c : closures) {
    within += c.nees <= kChiSquare6Bound95;
    within_r += c.nees_rotation <= kChiSquare3Bound95;
    within_t += c.nees_translation <= kChiSquare3Bound95;
    sum += c.nees;
    angles.push_back(c.residual.head<3>().norm() * 180.0 / M_PI);
    distances.push_back(c.residual.tail<3>().norm());
  }
  const double n = static_cast<double>(closures.size());
  char text[400];
  std::snprintf(text, sizeof(text),
                "%zu triangles: %.1f %% within the 95 %% bound of chi-square(6) "
                "(rotation %.1f %%, translation %.1f %% of chi-square(3)), mean NEES "
                "%.2f (6 if calibrated); median closure %.3f deg / %.4f m",
                closures.size(), 100.0 * within / n, 100.0 * within_r / n,
                100.0 * within_t / n, sum / n, median(angles), median(distances));
  return text;
}

} // namespace batch
} // namespace phaser
} // namespace pcl
