/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "so3/so3_correlation_grid.h"
#include "spatial/spatial_grid_support.h"
#include "support/error.h"
#include "support/parallel.h"
#include "uncertainty/peak_neighborhood.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

namespace pcl::phaser {

using detail::axisValues;
using detail::kLogFloor;
using detail::valueAtWrapped;
using detail::wrapIndex;

namespace {

/** Grid value at a possibly out-of-range index (see rotationNeighborhood). */
double valueAt(const So3CorrelationGrid& grid, int j, int a, int c)
{
  const int N = grid.size(), Bo = grid.outputBandwidth();
  if (j < 0 || j >= N) {
    j = j < 0 ? -1 - j : 2 * N - 1 - j;
    a += Bo;
    c -= Bo;
  }
  return grid(j, wrapIndex(a, N), wrapIndex(c, N));
}

} // namespace

std::vector<RotationSample> rotationNeighborhood(const So3CorrelationGrid& grid,
                                                 const So3GridIndex& peak, int radius)
{
  if (radius < 0)
    throw InvalidArgument("rotationNeighborhood: radius must be >= 0");
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

namespace {

struct PeakCandidate {
  double value;
  std::size_t flat; ///< (j * N + a) * N + c
};

/** The local maxima (26 neighbors, wrapping as valueAt does) of \a grid in the upper
 *  half of its value range (of the rows searched), best first (ties by flat index): the
 * value range per beta row, then the maxima per row joined in row order, whatever the
 * thread count. */
std::vector<PeakCandidate> upperLocalMaxima(const So3CorrelationGrid& grid, int threads)
{
  const int N = grid.size();
  // On a grid limited in tilt, the rows whose beta neighbors were computed (as argmax).
  const int R = grid.betaRows() < N ? std::max(1, grid.betaRows() - 1) : N;
  std::vector<double> row_lo(static_cast<std::size_t>(R)), row_hi(row_lo.size());
  std::vector<std::vector<PeakCandidate>> rows(static_cast<std::size_t>(R));
  detail::parallelFor(
      R, 4, threads, [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
        for (std::ptrdiff_t j = first; j < last; ++j) {
          // Four independent running extremes: one chain would wait on each comparison.
          constexpr double inf = std::numeric_limits<double>::infinity();
          double lo[4] = {inf, inf, inf, inf}, hi[4] = {-inf, -inf, -inf, -inf};
          for (int a = 0; a < N; ++a)
            for (int c = 0; c < N; ++c) {
              const double v = grid(j, a, c);
              lo[c & 3] = std::min(lo[c & 3], v);
              hi[c & 3] = std::max(hi[c & 3], v);
            }
          row_lo[j] = std::min(std::min(lo[0], lo[1]), std::min(lo[2], lo[3]));
          row_hi[j] = std::max(std::max(hi[0], hi[1]), std::max(hi[2], hi[3]));
        }
      });
  const double lo = *std::min_element(row_lo.begin(), row_lo.end());
  const double hi = *std::max_element(row_hi.begin(), row_hi.end());
  const double floor = lo + 0.5 * (hi - lo);
  detail::parallelFor(
      R, 4, threads, [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
        for (int j = static_cast<int>(first); j < last; ++j)
          for (int a = 0; a < N; ++a) {
            for (int c = 0; c < N; ++c) {
              const double v = grid(j, a, c);
              if (v < floor)
                continue;
              // The neighbors along c first: on a smooth grid one is usually higher.
              const double left =
                  c > 0 ? grid(j, a, c - 1) : valueAt(grid, j, a, c - 1);
              const double right =
                  c + 1 < N ? grid(j, a, c + 1) : valueAt(grid, j, a, c + 1);
              bool is_max = !(left > v) && !(right > v);
              for (int dj = -1; dj <= 1 && is_max; ++dj)
                for (int da = -1; da <= 1 && is_max; ++da)
                  for (int dc = -1; dc <= 1 && is_max; ++dc)
                    if ((dj || da || dc) && valueAt(grid, j + dj, a + da, c + dc) > v)
                      is_max = false;
              if (is_max)
                rows[j].push_back({v, (static_cast<std::size_t>(j) * N + a) * N + c});
            }
          }
      });
  std::vector<PeakCandidate> maxima;
  for (const std::vector<PeakCandidate>& row : rows)
    maxima.insert(maxima.end(), row.begin(), row.end());
  std::sort(maxima.begin(), maxima.end(),
            [](const PeakCandidate& x, const PeakCandidate& y) {
              return x.value > y.value || (x.value == y.value && x.flat < y.flat);
            });
  return maxima;
}

} // namespace

std::vector<So3GridIndex> distinctPeaks(const So3CorrelationGrid& grid, int count,
                                        double min_separation, int num_threads)
{
  const int N = grid.size();
  if (N <= 0)
    return {};
  // Grids of fewer than 128^3 samples (Bo < 64) are searched by the calling thread.
  const int threads = N < 128 ? 1 : std::max(1, num_threads);
  const std::vector<PeakCandidate> maxima = upperLocalMaxima(grid, threads);
  std::vector<So3GridIndex> peaks;
  std::vector<Eigen::Matrix3d> taken;
  for (const PeakCandidate& m : maxima) {
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

namespace {

/** Running mean and variance (Welford), deterministic for a fixed order. */
struct RunningVariance {
  double mean = 0.0, m2 = 0.0;
  std::size_t count = 0;
  void add(double v)
  {
    ++count;
    const double d = v - mean;
    mean += d / static_cast<double>(count);
    m2 += d * (v - mean);
  }
  double variance() const { return count > 1 ? m2 / static_cast<double>(count) : 0.0; }
};

} // namespace

CorrelationSidelobes correlationSidelobes(const SpatialVolume& correlation,
                                          const Eigen::Vector3i& peak)
{
  const Eigen::Vector3i& n = correlation.grid.dims;
  // The shell, clipped to the volume: a lag is visited once even if the box wraps.
  Eigen::Vector3i lo, hi;
  for (int a = 0; a < 3; ++a) {
    const int reach = std::min(kSidelobeOuterRadius, (n[a] - 1) / 2);
    lo[a] = -reach;
    hi[a] = reach;
  }
  RunningVariance first[3], second[3];
  for (int dx = lo.x(); dx <= hi.x(); ++dx)
    for (int dy = lo.y(); dy <= hi.y(); ++dy)
      for (int dz = lo.z(); dz <= hi.z(); ++dz) {
        if (std::abs(dx) <= kSidelobeInnerRadius &&
            std::abs(dy) <= kSidelobeInnerRadius &&
            std::abs(dz) <= kSidelobeInnerRadius)
          continue;
        const Eigen::Vector3i p = peak + Eigen::Vector3i(dx, dy, dz);
        for (int a = 0; a < 3; ++a) {
          if (n[a] < 3)
            continue;
          const Eigen::Vector3d v = axisValues(correlation, p, a);
          first[a].add(v[2] - v[0]);
          second[a].add(v[0] - 2.0 * v[1] + v[2]);
        }
      }
  CorrelationSidelobes out;
  for (int a = 0; a < 3; ++a) {
    out.first_difference_variance[a] = first[a].variance();
    out.second_difference_variance[a] = second[a].variance();
  }
  return out;
}

Eigen::Matrix3d subVoxelPeakCovariance(const SpatialVolume& correlation,
                                       const Eigen::Vector3i& peak,
                                       const CorrelationSidelobes& noise)
{
  const double voxel2 = correlation.grid.voxel_size * correlation.grid.voxel_size;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 3; ++a) {
    double var = 1.0 / 12.0; // no usable maximum on this axis: one voxel, uniform
    if (correlation.grid.dims[a] >= 3) {
      const Eigen::Vector3d v = axisValues(correlation, peak, a);
      const double va = v[0], vb = v[1], vd = v[2];
      // Fitted values and the factors that turn value errors into fitted-value errors.
      double fa = va, fb = vb, fd = vd, sa = 1.0, sd = 1.0;
      if (vb > 0.0 && va > kLogFloor * vb && vd > kLogFloor * vb) {
        fa = std::log(va);
        fb = std::log(vb);
        fd = std::log(vd);
        sa = 1.0 / va;
        sd = 1.0 / vd;
      }
      const double k = fa - 2.0 * fb + fd;
      if (k < 0.0) {
        // o = (fa - fd) / (2k): do/dfa = (1 - 2o) / (2k), do/dfd = -(1 + 2o) / (2k).
        const double o = std::clamp(0.5 * (fa - fd) / k, -0.5, 0.5);
        const double alpha = sa * (1.0 - 2.0 * o) / (2.0 * k);
        const double gamma = -sd * (1.0 + 2.0 * o) / (2.0 * k);
        var = 0.25 * (alpha - gamma) * (alpha - gamma) *
                  noise.first_difference_variance[a] +
              0.25 * (alpha + gamma) * (alpha + gamma) *
                  noise.second_difference_variance[a];
      }
    }
    cov(a, a) = var * voxel2;
  }
  return cov;
}

Eigen::Matrix3d interpolationModelCovariance(const SpatialVolume& correlation,
                                             const Eigen::Vector3i& peak)
{
  const double voxel2 = correlation.grid.voxel_size * correlation.grid.voxel_size;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 3; ++a) {
    if (correlation.grid.dims[a] < 3)
      continue;
    const Eigen::Vector3d v = axisValues(correlation, peak, a);
    const double va = v[0], vb = v[1], vd = v[2];
    const double k = va - 2.0 * vb + vd;
    if (!(vb > 0.0 && va > kLogFloor * vb && vd > kLogFloor * vb) || !(k < 0.0))
      continue; // one model only (or none): no disagreement to measure
    const double la = std::log(va), lb = std::log(vb), ld = std::log(vd);
    const double kl = la - 2.0 * lb + ld;
    if (!(kl < 0.0))
      continue;
    const double gaussian = std::clamp(0.5 * (la - ld) / kl, -0.5, 0.5);
    const double parabola = std::clamp(0.5 * (va - vd) / k, -0.5, 0.5);
    cov(a, a) = (gaussian - parabola) * (gaussian - parabola) * voxel2;
  }
  return cov;
}

Eigen::Matrix3d translationCovariance(const SpatialVolume& correlation,
                                      const Eigen::Vector3i& peak,
                                      double energy_product)
{
  if (!(energy_product > 0.0) || !std::isfinite(energy_product))
    throw InvalidArgument("translationCovariance: the energy product must be > 0");
  CorrelationSidelobes noise = correlationSidelobes(correlation, peak);
  const double c = valueAtWrapped(correlation, peak);
  // Mismatch fraction 1 - rho^2, kept >= 1e-6: identical clouds still differ by the
  // resampling of the voxel grid, and a zero would make the covariance singular.
  const double mismatch = std::clamp(1.0 - c * c / energy_product, 1e-6, 1.0);
  noise.first_difference_variance *= mismatch;
  noise.second_difference_variance *= mismatch;
  Eigen::Matrix3d cov = subVoxelPeakCovariance(correlation, peak, noise) +
                        interpolationModelCovariance(correlation, peak);
  // A volume without sidelobe fluctuation (e.g. a lone spike) gives zero noise; the
  // sub-voxel estimate is then exact up to round-off: keep the matrix definite.
  const double floor =
      1e-12 * correlation.grid.voxel_size * correlation.grid.voxel_size;
  for (int a = 0; a < 3; ++a)
    cov(a, a) = std::max(cov(a, a), floor);
  return cov;
}

double spectrumEnergy(const SpatialSpectrum& spectrum)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < spectrum.coefficients.size(); ++i)
    sum += spectrum.multiplicity(i) * std::norm(spectrum.coefficients[i]);
  return sum / static_cast<double>(spectrum.grid.size());
}

double rotationModelError(int bandwidth)
{
  if (bandwidth < 1)
    throw InvalidArgument("rotationModelError: bandwidth must be >= 1");
  return kRotationModelErrorScale * M_PI / bandwidth;
}

Eigen::Matrix3d rotationCovariance(const BinghamDistribution& peak, int bandwidth)
{
  const double s = rotationModelError(bandwidth);
  const Eigen::Matrix3d spread = peak.tangentCovariance(TangentFrame::kGlobal);
  return 0.5 * (spread + spread.transpose()) + s * s * Eigen::Matrix3d::Identity();
}

} // namespace pcl::phaser
