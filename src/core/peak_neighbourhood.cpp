/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include <pcl_phaser/core/error.h>
#include <pcl_phaser/core/peak_neighbourhood.h>
#include <pcl_phaser/core/so3_grid.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_phaser {

namespace {

inline int wrap(int i, int n)
{
  return ((i % n) + n) % n;
}

/** Grid value at a possibly out-of-range index (see rotationNeighbourhood). */
double valueAt(const So3CorrelationGrid& grid, int j, int a, int c)
{
  const int N = grid.size(), Bo = grid.outputBandwidth();
  if (j < 0 || j >= N) {
    j = j < 0 ? -1 - j : 2 * N - 1 - j;
    a += Bo;
    c -= Bo;
  }
  return grid(j, wrap(a, N), wrap(c, N));
}

} // namespace

std::vector<RotationSample> rotationNeighbourhood(const So3CorrelationGrid& grid,
                                                  const So3GridIndex& peak, int radius)
{
  if (radius < 0)
    throw InvalidArgument("rotationNeighbourhood: radius must be >= 0");
  const double Bo = grid.outputBandwidth();
  std::vector<RotationSample> out;
  for (int dj = -radius; dj <= radius; ++dj)
    for (int da = -radius; da <= radius; ++da)
      for (int dc = -radius; dc <= radius; ++dc) {
        const int j = peak.beta + dj, a = peak.alpha + da, c = peak.gamma + dc;
        // Euler angles of the unwrapped index: rotationFromEuler accepts any beta sign.
        const EulerZYZ e{M_PI * a / Bo, M_PI * (2 * j + 1) / (4.0 * Bo), M_PI * c / Bo};
        out.push_back({rotationFromEuler(e), valueAt(grid, j, a, c)});
      }
  return out;
}

std::vector<So3GridIndex> distinctPeaks(const So3CorrelationGrid& grid, int count,
                                        double min_separation)
{
  const int N = grid.size();
  struct Candidate {
    double value;
    std::size_t flat;
  };
  // Only samples in the upper half of the value range can be peaks worth reporting; the
  // 26-neighbour test then runs on few of them.
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int j = 0; j < N; ++j)
    for (int a = 0; a < N; ++a)
      for (int c = 0; c < N; ++c) {
        lo = std::min(lo, grid(j, a, c));
        hi = std::max(hi, grid(j, a, c));
      }
  const double floor = lo + 0.5 * (hi - lo);
  std::vector<Candidate> maxima;
  for (int j = 0; j < N; ++j)
    for (int a = 0; a < N; ++a)
      for (int c = 0; c < N; ++c) {
        const double v = grid(j, a, c);
        if (v < floor)
          continue;
        bool is_max = true;
        for (int dj = -1; dj <= 1 && is_max; ++dj)
          for (int da = -1; da <= 1 && is_max; ++da)
            for (int dc = -1; dc <= 1 && is_max; ++dc)
              if ((dj || da || dc) && valueAt(grid, j + dj, a + da, c + dc) > v)
                is_max = false;
        if (is_max)
          maxima.push_back({v, (static_cast<std::size_t>(j) * N + a) * N + c});
      }
  std::sort(maxima.begin(), maxima.end(), [](const Candidate& x, const Candidate& y) {
    return x.value > y.value || (x.value == y.value && x.flat < y.flat);
  });
  std::vector<So3GridIndex> peaks;
  std::vector<Eigen::Matrix3d> taken;
  for (const Candidate& m : maxima) {
    if (static_cast<int>(peaks.size()) >= count)
      break;
    const So3GridIndex idx{static_cast<int>(m.flat / (static_cast<std::size_t>(N) * N)),
                           static_cast<int>((m.flat / N) % N),
                           static_cast<int>(m.flat % N)};
    const Eigen::Matrix3d R = rotationFromEuler(gridEuler(idx, grid.outputBandwidth()));
    bool distinct = true;
    for (const Eigen::Matrix3d& T : taken)
      distinct = distinct && rotationDistance(R, T) > min_separation;
    if (distinct) {
      peaks.push_back(idx);
      taken.push_back(R);
    }
  }
  return peaks;
}

TranslationGaussian translationGaussian(const SpatialVolume& correlation,
                                        const Eigen::Vector3i& peak, int radius)
{
  if (radius < 1)
    throw InvalidArgument("translationGaussian: radius must be >= 1");
  const SpatialGrid& g = correlation.grid;
  std::vector<Eigen::Vector3d> lags;
  std::vector<double> values;
  double lowest = std::numeric_limits<double>::infinity();
  for (int dx = -radius; dx <= radius; ++dx)
    for (int dy = -radius; dy <= radius; ++dy)
      for (int dz = -radius; dz <= radius; ++dz) {
        const Eigen::Vector3i d(dx, dy, dz);
        Eigen::Vector3i idx;
        Eigen::Vector3d lag;
        for (int k = 0; k < 3; ++k) {
          idx[k] = wrap(peak[k] + d[k], g.dims[k]);
          int l = idx[k]; // signed lag: indices above n/2 are negative shifts
          if (l > g.dims[k] / 2)
            l -= g.dims[k];
          lag[k] = l;
        }
        const double v = correlation.values[g.flatIndex(idx.x(), idx.y(), idx.z())];
        lags.push_back(g.origin + lag * g.voxel_size);
        values.push_back(v);
        lowest = std::min(lowest, v);
      }
  TranslationGaussian out;
  double total = 0.0;
  for (std::size_t i = 0; i < lags.size(); ++i) {
    const double w = values[i] - lowest;
    out.mean += w * lags[i];
    total += w;
  }
  if (!(total > 0.0)) { // a flat block: no information beyond the peak itself
    out.mean = lags[lags.size() / 2];
    out.covariance = Eigen::Matrix3d::Identity() * std::pow(radius * g.voxel_size, 2);
    return out;
  }
  out.mean /= total;
  for (std::size_t i = 0; i < lags.size(); ++i) {
    const Eigen::Vector3d d = lags[i] - out.mean;
    out.covariance += (values[i] - lowest) / total * d * d.transpose();
  }
  return out;
}

} // namespace pcl_phaser
