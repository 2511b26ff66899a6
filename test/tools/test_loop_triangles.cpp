/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The reference-free covariance check on loop triangles (tools/loop_triangles.h):
 * edges measured with noise drawn from their covariances, in getCovariance()'s
 * convention, close with a chi-square(6) NEES; in another convention they do not.
 */
#include "batch_records.h"
#include "loop_triangles.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace {

namespace batch = pcl::phaser::batch;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

Eigen::Matrix3d exp3(const Eigen::Vector3d& w)
{
  return w.norm() < 1e-15 ? Eigen::Matrix3d::Identity()
                          : Eigen::AngleAxisd(w.norm(), w.normalized()).matrix();
}

/** A converged record of edge i -> j measuring \a T with \a C. */
batch::Record record(int i, int j, const Eigen::Matrix4d& T, const Matrix6d& C)
{
  batch::Pair pair;
  pair.source = "s" + std::to_string(j);
  pair.target = "t" + std::to_string(i);
  pair.source_id = j;
  pair.target_id = i;
  pcl::phaser::PhaserResult result;
  result.transformation = T;
  result.converged = true;
  result.covariance = C;
  return batch::alignedRecord(pair, 1, result, 1.0);
}

/** Closures of 8 scans 10 m and any rotation apart, all 28 edges measured: T_est from
 *  the truth by omega, nu ~ N(0, C) with R_true = Exp(omega) R_est, t_true = t_est + nu
 *  (target frame), a third of them with the later scan as target; \a source_frame draws
 *  them in the source's frame instead. */
std::vector<batch::Closure> simulate(std::mt19937& rng, bool source_frame)
{
  std::normal_distribution<double> n01;
  const auto gaussian = [&](int k) {
    return Eigen::VectorXd(Eigen::VectorXd::NullaryExpr(k, [&] { return n01(rng); }));
  };
  std::vector<Eigen::Matrix4d> world(8, Eigen::Matrix4d::Identity());
  for (Eigen::Matrix4d& T : world) {
    T.topLeftCorner<3, 3>() = exp3(gaussian(3) * 1.5);
    T.topRightCorner<3, 1>() = 10.0 * gaussian(3);
  }
  std::vector<batch::Record> records;
  for (int i = 0; i < 8; ++i)
    for (int j = i + 1; j < 8; ++j) {
      // Far from isotropic (standard deviations 0.003-1 mrad or mm along random axes),
      // so that noise drawn in another frame does not pass for this one's.
      const Eigen::Matrix<double, 6, 1> s =
          (Eigen::Matrix<double, 6, 1>() << 3e-6, 1e-5, 1e-4, 3e-6, 1e-4, 1e-3)
              .finished();
      const Matrix6d Q =
          Eigen::HouseholderQR<Matrix6d>(Matrix6d::Random()).householderQ();
      const Matrix6d C = Q * s.cwiseAbs2().asDiagonal() * Q.transpose();
      const Eigen::Matrix<double, 6, 1> d =
          Eigen::LLT<Matrix6d>(C).matrixL() * Eigen::Matrix<double, 6, 1>(gaussian(6));
      // Every third edge measured the other way (the later scan as target), its noise
      // drawn in its own target frame: the check inverts it with its own Jacobian.
      const bool reversed = (i + j) % 3 == 0;
      const int target = reversed ? j : i, source = reversed ? i : j;
      const Eigen::Matrix4d truth = world[target].inverse() * world[source];
      Eigen::Matrix4d T = truth;
      Eigen::Vector3d w = d.head<3>(), v = d.tail<3>();
      if (source_frame) {
        w = truth.topLeftCorner<3, 3>() * w;
        v = truth.topLeftCorner<3, 3>() * v;
      }
      T.topLeftCorner<3, 3>() = exp3(-w) * truth.topLeftCorner<3, 3>();
      T.topRightCorner<3, 1>() -= v;
      records.push_back(record(target, source, T, C));
    }
  return batch::loopClosures(records);
}

} // namespace

TEST(LoopTriangles, NoiseFromTheCovariancesGivesChiSquareSix)
{
  std::mt19937 rng(3);
  double sum = 0.0, wrong = 0.0;
  int n = 0, within = 0;
  for (int run = 0; run < 30; ++run) {
    for (const batch::Closure& c : simulate(rng, false)) {
      sum += c.nees;
      within += c.nees <= batch::kChiSquare6Bound95;
      ++n;
    }
    for (const batch::Closure& c : simulate(rng, true))
      wrong += c.nees;
  }
  std::printf(
      "  mean NEES %.2f, %.3f within the 95 %% bound; in the source's frame %.2f\n",
      sum / n, static_cast<double>(within) / n, wrong / n);
  EXPECT_EQ(n, 30 * 56); // C(8, 3) triangles a run
  EXPECT_NEAR(sum / n, 6.0, 0.3);
  EXPECT_NEAR(static_cast<double>(within) / n, 0.95, 0.015);
  // The same noise in the source's frame: the check tells it apart.
  EXPECT_GT(wrong / n, 9.0);
}

TEST(LoopTriangles, EdgesEitherWayAndMissingOnesFormTheTriangles)
{
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T(0, 3) = 1.0;
  const Matrix6d C = 1e-4 * Matrix6d::Identity();
  // 0 -> 1 and 1 -> 2 along x, 0 -> 2 as 2 -> 0 (the inverse): one exact triangle.
  Eigen::Matrix4d back = Eigen::Matrix4d::Identity();
  back(0, 3) = -2.0;
  const std::vector<batch::Record> records = {record(0, 1, T, C), record(1, 2, T, C),
                                              record(2, 0, back, C),
                                              record(1, 3, T, C)};
  const std::vector<batch::Closure> closures = batch::loopClosures(records);
  ASSERT_EQ(closures.size(), 1u);
  EXPECT_EQ(closures[0].a, 0);
  EXPECT_EQ(closures[0].c, 2);
  EXPECT_NEAR(closures[0].nees, 0.0, 1e-12);
  EXPECT_EQ(batch::closureSummary({}), "no triangle of converged edges");
}
