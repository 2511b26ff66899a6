/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "channels/spectral_fusion.h"
#include "support/error.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

namespace pcl::phaser {
namespace {

using Complex = std::complex<double>;

void checkLevels(int levels)
{
  if (levels < 1)
    throw InvalidArgument("fusion levels must be >= 1, got " + std::to_string(levels));
}

/** Band of degree l at bandwidth B (no checks): 0 below B / 2^(L-1), then one band
 *  per octave, in exact integer arithmetic. */
int bandOfDegree(int degree, int bandwidth, int levels)
{
  if (degree == 0)
    return 0;
  long long p = degree; // degree * 2^j, stops below 2B, so no overflow
  int j = 0;
  while (j < levels - 1 && 2 * p < bandwidth) {
    p *= 2;
    ++j;
  }
  return levels - 1 - j;
}

/** Mean anchored at the first channel, x0 + sum (x_c - x0) / K: equal channels give
 *  x0 bit for bit, which a plain sum / K does not guarantee (3x / 3 may round). */
template <typename Get>
Complex anchoredMean(std::size_t K, const Get& get)
{
  const Complex x0 = get(0);
  Complex sum = 0.0;
  for (std::size_t c = 1; c < K; ++c)
    sum += get(c) - x0;
  return x0 + sum / static_cast<double>(K);
}

/** Index of the largest value; ties (and NaN) keep the lowest index. */
int argmaxLowest(const double* values, std::size_t K)
{
  std::size_t best = 0;
  for (std::size_t c = 1; c < K; ++c)
    if (values[c] > values[best])
      best = c;
  return static_cast<int>(best);
}

void checkSpherical(const std::vector<SphericalSpectrum>& channels,
                    const FusionParameters& parameters)
{
  checkLevels(parameters.levels);
  if (parameters.degree_radius < 0)
    throw InvalidArgument("fusion degree_radius must be >= 0, got " +
                          std::to_string(parameters.degree_radius));
  if (channels.empty())
    throw InvalidArgument("spherical fusion needs at least one channel");
  const Eigen::Index B = channels.front().rows();
  if (B < 1 || channels.front().cols() != B)
    throw InvalidArgument("spherical fusion: spectra must be B x B with B >= 1");
  for (const SphericalSpectrum& F : channels)
    if (F.rows() != B || F.cols() != B)
      throw InvalidArgument("spherical fusion: channel spectra differ in bandwidth");
}

/** Indices of the channels with a non-zero coefficient (all of them when none has):
 *  an absent channel would scale the averaged band down against the selected ones. */
std::vector<std::size_t>
presentSpherical(const std::vector<SphericalSpectrum>& channels)
{
  std::vector<std::size_t> present;
  for (std::size_t c = 0; c < channels.size(); ++c)
    if (!channels[c].isZero(0.0))
      present.push_back(c);
  if (present.empty())
    for (std::size_t c = 0; c < channels.size(); ++c)
      present.push_back(c);
  return present;
}

/** Energy of each degree of a real function's spectrum, |F(l,0)|^2 + 2 sum_{m>=1}
 *  |F(l,m)|^2: rotation-invariant, as a rotation mixes a degree's orders unitarily. */
std::vector<double> sphericalDegreeEnergy(const SphericalSpectrum& F)
{
  const Eigen::Index B = std::min(F.rows(), F.cols());
  std::vector<double> energy(static_cast<std::size_t>(F.rows()), 0.0);
  for (Eigen::Index l = 0; l < B; ++l) {
    double e = std::norm(F(l, 0));
    // m > 0 stands for the orders +m and -m, which have equal magnitude.
    for (Eigen::Index m = 1; m <= l; ++m)
      e += 2.0 * std::norm(F(l, m));
    energy[l] = e;
  }
  return energy;
}

/** The choice per degree as an index into \a present (-1 = averaged). */
std::vector<int> sphericalChoice(const std::vector<SphericalSpectrum>& all,
                                 const std::vector<std::size_t>& present,
                                 const FusionParameters& parameters)
{
  const int B = static_cast<int>(all.front().rows());
  const std::size_t K = present.size();
  // degree[l * K + c]: energy of channel c at degree l; window[c]: its sum over the
  // degrees l - r .. l + r (reaching into neighboring bands).
  std::vector<double> degree(static_cast<std::size_t>(B) * K);
  for (std::size_t c = 0; c < K; ++c) {
    const std::vector<double> e = sphericalDegreeEnergy(all[present[c]]);
    for (int l = 0; l < B; ++l)
      degree[l * K + c] = e[l];
  }
  const int r = parameters.degree_radius;
  std::vector<int> choice(B, -1);
  std::vector<double> window(K);
  for (int l = 0; l < B; ++l) {
    if (bandOfDegree(l, B, parameters.levels) == 0)
      continue;
    std::fill(window.begin(), window.end(), 0.0);
    for (int d = std::max(0, l - r); d <= std::min(B - 1, l + r); ++d)
      for (std::size_t c = 0; c < K; ++c)
        window[c] += degree[d * K + c];
    choice[l] = argmaxLowest(window.data(), K);
  }
  return choice;
}

/** Median of v (mean of the two middle values for even sizes); reorders v. */
double medianInPlace(std::vector<double>& v)
{
  const std::size_t n = v.size(), h = n / 2;
  std::nth_element(v.begin(), v.begin() + h, v.end());
  const double upper = v[h];
  if (n % 2 == 1)
    return upper;
  const double lower = *std::max_element(v.begin(), v.begin() + h);
  return lower + 0.5 * (upper - lower); // no overflow for huge values of equal sign
}

} // namespace

int sphericalBand(int degree, int bandwidth, int levels)
{
  checkLevels(levels);
  if (bandwidth < 1 || degree < 0 || degree >= bandwidth)
    throw InvalidArgument("sphericalBand: need 0 <= degree < bandwidth, got degree " +
                          std::to_string(degree) + ", bandwidth " +
                          std::to_string(bandwidth));
  return bandOfDegree(degree, bandwidth, levels);
}

std::vector<int> selectSphericalChannels(const std::vector<SphericalSpectrum>& channels,
                                         const FusionParameters& parameters)
{
  checkSpherical(channels, parameters);
  const std::vector<std::size_t> present = presentSpherical(channels);
  std::vector<int> choice = sphericalChoice(channels, present, parameters);
  for (int& c : choice)
    if (c >= 0)
      c = static_cast<int>(present[c]);
  return choice;
}

SphericalSpectrum fuseSpherical(const std::vector<SphericalSpectrum>& channels,
                                const FusionParameters& parameters)
{
  checkSpherical(channels, parameters);
  const std::vector<std::size_t> present = presentSpherical(channels);
  if (present.size() == 1)
    return channels[present.front()];
  const std::vector<int> choice = sphericalChoice(channels, present, parameters);
  const int B = static_cast<int>(channels.front().rows());
  const std::size_t K = present.size();
  SphericalSpectrum fused = SphericalSpectrum::Zero(B, B);
  for (int l = 0; l < B; ++l)
    for (int m = 0; m <= l; ++m)
      fused(l, m) = choice[l] >= 0 ? channels[present[choice[l]]](l, m)
                                   : anchoredMean(K, [&](std::size_t c) {
                                       return channels[present[c]](l, m);
                                     });
  return fused;
}

Eigen::VectorXd normalizeChannel(const Eigen::VectorXd& values, double clamp)
{
  if (!(clamp > 0.0) || !std::isfinite(clamp))
    throw InvalidArgument("normalizeChannel: clamp must be finite and > 0");
  Eigen::VectorXd out = Eigen::VectorXd::Zero(values.size());
  std::vector<double> work;
  work.reserve(static_cast<std::size_t>(values.size()));
  for (Eigen::Index i = 0; i < values.size(); ++i)
    if (std::isfinite(values[i]))
      work.push_back(values[i]);
  if (work.empty())
    return out;
  const double median = medianInPlace(work);
  // Median and MAD ignore up to half of the values being wild (saturated returns,
  // retro-reflectors), unlike mean and standard deviation.
  for (double& v : work)
    v = std::abs(v - median);
  const double mean_deviation = [&] {
    double s = 0.0;
    for (double v : work)
      s += v;
    return s / static_cast<double>(work.size());
  }();
  double scale = 1.482602218505602 * medianInPlace(work); // 1 / Phi^-1(3/4)
  if (!(scale > 0.0))
    scale = 1.2533141373155003 * mean_deviation; // sqrt(pi / 2)
  if (!(scale > 0.0) || !std::isfinite(scale))
    return out; // constant channel: no information, contributes nothing
  for (Eigen::Index i = 0; i < values.size(); ++i)
    if (std::isfinite(values[i]))
      out[i] = std::clamp((values[i] - median) / scale, -clamp, clamp);
  return out;
}

} // namespace pcl::phaser
