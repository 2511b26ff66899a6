/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "so3/so3_correlation_grid.h"
#include "support/buffer_pool.h"
#include "support/error.h"
#include "support/fftw_support.h"
#include "support/parallel.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace pcl::phaser {

Eigen::Matrix3d rotationFromEuler(const EulerZYZ& e)
{
  return (Eigen::AngleAxisd(e.alpha, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(e.beta, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(e.gamma, Eigen::Vector3d::UnitZ()))
      .toRotationMatrix();
}

EulerZYZ eulerFromRotation(const Eigen::Matrix3d& R)
{
  EulerZYZ e;
  const double sb = std::hypot(R(0, 2), R(1, 2));
  e.beta = std::atan2(sb, R(2, 2));
  if (sb > 1e-12) {
    e.alpha = std::atan2(R(1, 2), R(0, 2));
    e.gamma = std::atan2(R(2, 1), -R(2, 0));
  } else if (R(2, 2) > 0.0) {
    e.alpha = std::atan2(R(1, 0), R(0, 0));
  } else {
    e.alpha = std::atan2(-R(1, 0), -R(0, 0));
  }
  return e;
}

EulerZYZ gridEuler(const So3GridIndex& i, int output_bandwidth)
{
  const double bo = output_bandwidth;
  return {M_PI * i.alpha / bo, M_PI * (2 * i.beta + 1) / (4.0 * bo),
          M_PI * i.gamma / bo};
}

double rotationDistance(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B)
{
  // Via the quaternion (2 atan2), accurate for tiny angles, unlike acos of the trace.
  return Eigen::AngleAxisd(Eigen::Matrix3d(A.transpose() * B)).angle();
}

int betaRowsForTilt(int output_bandwidth, double max_tilt)
{
  checkBandwidth(output_bandwidth, "output bandwidth");
  const int N = 2 * output_bandwidth;
  if (!(max_tilt >= 0.0))
    throw InvalidArgument("betaRowsForTilt: the tilt must be >= 0");
  // beta_j = pi (2j + 1) / (4 Bo) <= max_tilt for j <= (4 Bo max_tilt / pi - 1) / 2.
  const double last =
      std::floor((4.0 * output_bandwidth * max_tilt / M_PI - 1.0) / 2.0);
  if (!(last < N))
    return N;
  return std::min(N, std::max(0, static_cast<int>(last) + 1) + 1);
}

void So3CorrelationGrid::FftwFree::operator()(double* p) const
{
  detail::bufferRelease(p, bytes);
}

void So3CorrelationGrid::accumulate(const So3CorrelationGrid& other)
{
  if (other.output_bandwidth_ != output_bandwidth_ || other.beta_rows_ != beta_rows_)
    throw InvalidArgument("So3CorrelationGrid::accumulate: grids differ");
  const std::size_t n = static_cast<std::size_t>(beta_rows_) * size() * row_stride_;
  for (std::size_t i = 0; i < n; ++i)
    data_[i] += other.data_[i];
}

So3GridIndex So3CorrelationGrid::argmax(int num_threads) const
{
  // The best of each beta row (first on ties), then the rows in order: the first
  // maximum in flat order whatever the thread count.
  const int N = size();
  const int rows = beta_rows_ < N ? std::max(1, beta_rows_ - 1) : N;
  std::vector<So3GridIndex> best(static_cast<std::size_t>(rows));
  std::vector<double> best_value(static_cast<std::size_t>(rows),
                                 -std::numeric_limits<double>::infinity());
  // Grids of fewer than 128^3 samples (Bo < 64) are searched by the calling thread.
  const int threads = N < 128 ? 1 : std::max(1, num_threads);
  detail::parallelFor(
      rows, 4, threads, [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
        for (int j = static_cast<int>(first); j < last; ++j)
          for (int a = 0; a < N; ++a) {
            const double* row =
                data_.get() + (static_cast<std::size_t>(j) * N + a) * row_stride_;
            for (int c = 0; c < N; ++c)
              if (row[c] > best_value[j]) {
                best_value[j] = row[c];
                best[j] = {j, a, c};
              }
          }
      });
  std::size_t winner = 0;
  for (std::size_t j = 1; j < best.size(); ++j)
    if (best_value[j] > best_value[winner])
      winner = j;
  return best.empty() ? So3GridIndex{} : best[winner];
}

So3GridIndex So3CorrelationGrid::argmaxNearIdentity(double radius) const
{
  // ZYZ angles (alpha, beta, gamma) have the quaternion w = cos(beta / 2) cos((alpha +
  // gamma) / 2), so the angle to the identity is 2 acos|w|; beta grows with the row.
  const int N = size();
  const int Bo = output_bandwidth_;
  So3GridIndex best{}, nearest{};
  double best_value = -std::numeric_limits<double>::infinity();
  double nearest_angle = std::numeric_limits<double>::infinity();
  // The angle depends on the row and on a + c only: one table per row, the same
  // expression as per sample.
  std::vector<double> angles(2 * static_cast<std::size_t>(N));
  for (int j = 0; j < N; ++j) {
    const double cos_half_beta = std::cos(0.5 * gridEuler({j, 0, 0}, Bo).beta);
    if (2.0 * std::acos(cos_half_beta) > std::max(radius, nearest_angle))
      break;
    for (int sum = 0; sum < 2 * N; ++sum) {
      const double half_sum = 0.5 * M_PI * sum / Bo;
      const double w = std::min(1.0, std::abs(cos_half_beta * std::cos(half_sum)));
      angles[static_cast<std::size_t>(sum)] = 2.0 * std::acos(w);
    }
    for (int a = 0; a < N; ++a) {
      const double* row =
          data_.get() + (static_cast<std::size_t>(j) * N + a) * row_stride_;
      const double* angle = angles.data() + a;
      for (int c = 0; c < N; ++c) {
        if (angle[c] < nearest_angle) {
          nearest_angle = angle[c];
          nearest = {j, a, c};
        }
        if (angle[c] <= radius && row[c] > best_value) {
          best_value = row[c];
          best = {j, a, c};
        }
      }
    }
  }
  return best_value > -std::numeric_limits<double>::infinity() ? best : nearest;
}

} // namespace pcl::phaser
