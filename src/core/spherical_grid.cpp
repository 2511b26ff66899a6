/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include <pcl_phaser/core/error.h>
#include <pcl_phaser/core/spherical_grid.h>

#include <algorithm>
#include <cmath>

namespace pcl::phaser {

double ringColatitude(int ring, int bandwidth)
{
  return M_PI * (2 * ring + 1) / (4.0 * bandwidth);
}

double columnAzimuth(int column, int bandwidth)
{
  return M_PI * column / bandwidth;
}

std::vector<double> quadratureWeights(int bandwidth)
{
  checkBandwidth(bandwidth);
  const int n = 2 * bandwidth;
  std::vector<double> w(n);
  for (int j = 0; j < n; ++j) {
    const double theta = ringColatitude(j, bandwidth);
    double sum = 0.0;
    for (int k = 0; k < bandwidth; ++k)
      sum += std::sin((2 * k + 1) * theta) / (2 * k + 1);
    w[j] = (2.0 / bandwidth) * std::sin(theta) * sum;
  }
  return w;
}

Eigen::Vector3d sampleDirection(int ring, int column, int bandwidth)
{
  const double t = ringColatitude(ring, bandwidth);
  const double p = columnAzimuth(column, bandwidth);
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

int cellIndex(const Eigen::Vector3d& p, int bandwidth)
{
  if (!p.allFinite())
    return -1;
  const double rho = std::hypot(p.x(), p.y());
  if (rho == 0.0 && p.z() == 0.0)
    return -1;
  const int n = 2 * bandwidth;
  // Cell j spans colatitudes [pi j / 2B, pi (j+1) / 2B): its sample theta_j is the
  // center.
  const double theta = std::atan2(rho, p.z());
  double phi = std::atan2(p.y(), p.x());
  if (phi < 0.0)
    phi += 2.0 * M_PI;
  const int j = std::min(n - 1, static_cast<int>(theta * n / M_PI));
  // Column k is centered on phi_k = pi k / B: round to the nearest sample.
  const int k = static_cast<int>(std::lround(phi * bandwidth / M_PI)) % n;
  return j * n + k;
}

} // namespace pcl::phaser
