/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include <pcl_phaser/core/error.h>
#include <pcl_phaser/core/spherical_grid.h>
#include <pcl_phaser/core/spherical_sampling.h>

#include <algorithm>
#include <cmath>

namespace pcl_phaser {

SphericalSamples sampleSphere(const Eigen::Matrix3Xd& points, int bandwidth,
                              const Eigen::VectorXd* values, int num_threads)
{
  checkBandwidth(bandwidth);
  if (values && values->size() != points.cols())
    throw InvalidArgument("sampleSphere: one value per point is required");
  const std::size_t cells = 4 * static_cast<std::size_t>(bandwidth) * bandwidth;
  SphericalSamples out;
  out.bandwidth = bandwidth;
  out.values.assign(cells, 0.0);
  std::vector<int> counts(cells, 0);
  // Cell lookup (two atan2 per point) is a pure function of the point: parallel; the
  // accumulation stays sequential in point order, so any thread count gives the same
  // bits.
  const Eigen::Index n = points.cols();
  std::vector<int> cell_of(static_cast<std::size_t>(n));
#pragma omp parallel for num_threads(std::max(1, num_threads)) schedule(static)
  for (Eigen::Index i = 0; i < n; ++i)
    cell_of[i] = cellIndex(points.col(i), bandwidth);
  for (Eigen::Index i = 0; i < n; ++i) {
    const int cell = cell_of[i];
    if (cell < 0)
      continue;
    const double v = values ? (*values)[i] : points.col(i).norm();
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
