/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include <pcl_phaser/core/error.h>
#include <pcl_phaser/core/spherical_grid.h>
#include <pcl_phaser/core/spherical_sampling.h>

#include <cmath>

namespace pcl_phaser {

SphericalSamples sampleSphere(const Eigen::Matrix3Xd& points, int bandwidth,
                              const Eigen::VectorXd* values)
{
  checkBandwidth(bandwidth);
  if (values && values->size() != points.cols())
    throw InvalidArgument("sampleSphere: one value per point is required");
  const std::size_t cells = 4 * static_cast<std::size_t>(bandwidth) * bandwidth;
  SphericalSamples out;
  out.bandwidth = bandwidth;
  out.values.assign(cells, 0.0);
  std::vector<int> counts(cells, 0);
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const Eigen::Vector3d p = points.col(i);
    const int cell = cellIndex(p, bandwidth);
    if (cell < 0)
      continue;
    const double v = values ? (*values)[i] : p.norm();
    if (!std::isfinite(v))
      continue;
    out.values[cell] += v;
    ++counts[cell];
  }
  double sum = 0.0;
  for (std::size_t c = 0; c < cells; ++c)
    if (counts[c]) {
      out.values[c] /= counts[c];
      sum += out.values[c];
      ++out.observed_cells;
    }
  if (out.observed_cells == 0)
    return out;
  const double mean = sum / out.observed_cells;
  for (std::size_t c = 0; c < cells; ++c)
    if (counts[c])
      out.values[c] -= mean;
  return out;
}

} // namespace pcl_phaser
