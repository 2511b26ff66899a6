/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "channels/spectral_magnitude.h"
#include "so3/so3_correlation.h"
#include "support/error.h"

#include <cmath>

namespace pcl::phaser {
namespace {

/** Shell frequencies, cycles per voxel: from the object's outline (a few voxels per
 *  cycle at the top) to its shape; on the bunny views this band put the truth above
 *  3,000 random rotations on 8 of 12 overlapping pairs. */
constexpr double kLowestFrequency = 0.05;
constexpr double kHighestFrequency = 0.35;
constexpr int kShells = 8;

/** |F| at the frequency \a f (cycles per voxel), trilinear over the 8 coefficients
 *  around it; negative kz through F(-k) = conj F(k). */
double magnitudeAt(const SpatialSpectrum& spectrum, Eigen::Vector3d f)
{
  if (f.z() < 0.0)
    f = -f;
  const Eigen::Vector3i& n = spectrum.grid.dims;
  const Eigen::Vector3d u(f.x() * n.x(), f.y() * n.y(), f.z() * n.z());
  const Eigen::Vector3d base = u.array().floor();
  const Eigen::Vector3d w = u - base;
  const int hz = spectrum.halfZ();
  double value = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const int dx = corner & 1, dy = (corner >> 1) & 1, dz = (corner >> 2) & 1;
    const int ix = ((static_cast<int>(base.x()) + dx) % n.x() + n.x()) % n.x();
    const int iy = ((static_cast<int>(base.y()) + dy) % n.y() + n.y()) % n.y();
    const int iz = std::min(static_cast<int>(base.z()) + dz, hz - 1);
    const double weight = (dx ? w.x() : 1.0 - w.x()) * (dy ? w.y() : 1.0 - w.y()) *
                          (dz ? w.z() : 1.0 - w.z());
    const std::size_t flat =
        (static_cast<std::size_t>(ix) * n.y() + static_cast<std::size_t>(iy)) * hz +
        static_cast<std::size_t>(iz);
    value += weight * std::abs(spectrum.coefficients[flat]);
  }
  return value;
}

/** \a values (2B x 2B rows) less their area-weighted mean, over their deviation. */
void standardize(std::vector<double>& values, int bandwidth)
{
  const int rows = 2 * bandwidth;
  double total = 0.0, sum = 0.0, squares = 0.0;
  for (int j = 0; j < rows; ++j) {
    const double area = std::sin(M_PI * (2 * j + 1) / (4.0 * bandwidth));
    for (int k = 0; k < rows; ++k) {
      const double v = values[static_cast<std::size_t>(j) * rows + k];
      total += area;
      sum += area * v;
      squares += area * v * v;
    }
  }
  const double mean = sum / total;
  const double deviation = std::sqrt(std::max(0.0, squares / total - mean * mean));
  for (double& v : values)
    v = deviation > 0.0 ? (v - mean) / deviation : 0.0;
}

} // namespace

MagnitudeShells magnitudeShells(const SpatialSpectrum& spectrum, int bandwidth)
{
  if (spectrum.coefficients.empty())
    throw InvalidArgument("magnitudeShells: empty spectrum");
  const auto sht = SphericalHarmonicTransform::instance(bandwidth);
  const int rows = 2 * bandwidth;
  MagnitudeShells out;
  double squared = 0.0;
  for (int s = 0; s < kShells; ++s) {
    const double radius =
        kLowestFrequency + (kHighestFrequency - kLowestFrequency) * s / (kShells - 1.0);
    std::vector<double> values(static_cast<std::size_t>(rows) * rows);
    for (int j = 0; j < rows; ++j) {
      const double theta = M_PI * (2 * j + 1) / (4.0 * bandwidth);
      for (int k = 0; k < rows; ++k) {
        const double phi = M_PI * k / bandwidth;
        const Eigen::Vector3d direction(std::sin(theta) * std::cos(phi),
                                        std::sin(theta) * std::sin(phi),
                                        std::cos(theta));
        values[static_cast<std::size_t>(j) * rows + k] =
            std::log1p(magnitudeAt(spectrum, radius * direction));
      }
    }
    standardize(values, bandwidth);
    out.shells.push_back(sht->forward(values.data()));
    squared += spectrumSquaredNorm(out.shells.back());
  }
  out.norm = std::sqrt(squared);
  return out;
}

So3CorrelationGrid correlateShells(const MagnitudeShells& target,
                                   const MagnitudeShells& source, int num_threads)
{
  if (target.shells.empty() || target.shells.size() != source.shells.size())
    throw InvalidArgument("correlateShells: the shells do not match");
  const auto correlator =
      So3Correlator::instance(static_cast<int>(target.shells.front().rows()));
  So3CorrelationGrid sum =
      correlator->correlate(target.shells.front(), source.shells.front(), num_threads);
  for (std::size_t s = 1; s < target.shells.size(); ++s)
    sum.accumulate(
        correlator->correlate(target.shells[s], source.shells[s], num_threads));
  return sum;
}

} // namespace pcl::phaser
