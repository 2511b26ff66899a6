/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "channels/cloud_signals.h"
#include "channels/spectral_fusion.h"
#include "sphere/spherical_sampling.h"
#include "support/error.h"

#include <algorithm>
#include <chrono>

namespace pcl::phaser {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

} // namespace

ChannelValues normalizeChannels(const ChannelValues& channels, Eigen::Index n)
{
  ChannelValues out;
  for (const Eigen::VectorXd& c : channels) {
    if (c.size() != n)
      throw InvalidArgument("every channel needs one value per point");
    out.push_back(normalizeChannel(c));
  }
  return out;
}

SphericalSpectrum cloudSphericalSpectrum(const Eigen::Matrix3Xd& points,
                                         const ChannelValues& channels, int bandwidth,
                                         int levels, int num_threads,
                                         int& observed_cells, double& sampling_ms,
                                         double& sht_ms, SphericalSupport* support)
{
  auto t = Clock::now();
  const std::vector<int> cells = sphereCells(points, bandwidth, num_threads);
  std::vector<SphericalSamples> samples;
  samples.push_back(binOnSphere(cells, points.colwise().norm().transpose(), bandwidth));
  for (const Eigen::VectorXd& c : channels)
    samples.push_back(binOnSphere(cells, c, bandwidth));
  observed_cells = samples.front().observed_cells;
  sampling_ms += msSince(t);
  t = Clock::now();
  const auto sht = SphericalHarmonicTransform::instance(bandwidth);
  std::vector<SphericalSpectrum> spectra;
  for (const SphericalSamples& s : samples)
    spectra.push_back(sht->forward(s.values.data(), num_threads));
  FusionParameters fusion;
  fusion.levels = levels;
  SphericalSpectrum fused =
      spectra.size() == 1 ? std::move(spectra.front()) : fuseSpherical(spectra, fusion);
  if (support) {
    // Observed cells are those of the range samples (every point has a finite range).
    std::vector<double> mask(samples.front().values.size(), 0.0);
    for (const int cell : cells)
      if (cell >= 0)
        mask[cell] = 1.0;
    // The energy of the signal that is correlated: the range samples themselves, or
    // the fused function (band-limited, so read back on the observed cells only).
    std::vector<double> energy =
        spectra.size() == 1 ? samples.front().values : sht->inverse(fused);
    for (std::size_t c = 0; c < energy.size(); ++c)
      energy[c] = mask[c] * energy[c] * energy[c];
    support->mask = sht->forward(mask.data(), num_threads);
    support->energy = sht->forward(energy.data(), num_threads);
  }
  sht_ms += msSince(t);
  return fused;
}

} // namespace pcl::phaser
