/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "sphere/spherical_grid.h"
#include "support/error.h"

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

namespace {

/** The largest error of fastAtan2, in radians, with a margin. */
constexpr double kFastAtanError = 2e-5;

/** atan(x) for 0 <= x <= 1 within 1e-5 rad (Abramowitz and Stegun 4.4.49). */
double atanUnit(double x)
{
  const double x2 = x * x;
  return x * (0.9998660 + x2 * (-0.3302995 +
                                x2 * (0.1801410 + x2 * (-0.0851330 + x2 * 0.0208351))));
}

/** atan2(y, x) within kFastAtanError, for (x, y) not both zero. */
double fastAtan2(double y, double x)
{
  const double ax = std::abs(x), ay = std::abs(y);
  double a = ay <= ax ? atanUnit(ay / ax) : M_PI_2 - atanUnit(ax / ay);
  if (x < 0.0)
    a = M_PI - a;
  return y < 0.0 ? -a : a;
}

/** The cell of \a p from the exact angles (two atan2). */
int exactCellIndex(const Eigen::Vector3d& p, int bandwidth)
{
  const double rho = std::hypot(p.x(), p.y());
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

} // namespace

int cellIndex(const Eigen::Vector3d& p, int bandwidth)
{
  if (!p.allFinite())
    return -1;
  if (p.x() == 0.0 && p.y() == 0.0 && p.z() == 0.0)
    return -1;
  // The angles from a polynomial: the cell is the exact one unless an angle lies
  // within the polynomial's error of a cell boundary, where the exact angles decide.
  const double rho2 = p.x() * p.x() + p.y() * p.y();
  if (!(rho2 > 1e-280 && rho2 < 1e280 && std::abs(p.z()) < 1e140))
    return exactCellIndex(p, bandwidth);
  const int n = 2 * bandwidth;
  const double margin = kFastAtanError * n / M_PI;
  const double u = fastAtan2(std::sqrt(rho2), p.z()) * n / M_PI;
  double v = fastAtan2(p.y(), p.x()) * bandwidth / M_PI;
  if (v < 0.0)
    v += n;
  const double j = std::floor(u), k = std::round(v);
  if (u - j < margin || j + 1.0 - u < margin || std::abs(v - k) > 0.5 - margin ||
      j >= n)
    return exactCellIndex(p, bandwidth);
  return static_cast<int>(j) * n + static_cast<int>(k) % n;
}

} // namespace pcl::phaser
