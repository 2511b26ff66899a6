/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "sphere/spherical_grid.h"
#include "sphere/spherical_harmonics.h"
#include "support/error.h"
#include "support/fftw_support.h"
#include "support/instance_cache.h"
#include "support/parallel.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstring>

namespace pcl::phaser {

using Complex = std::complex<double>;

namespace {

/** Bandwidths below this are transformed by the calling thread: at B = 64 (0.5 ms)
 *  waking a parked worker costs more. */
constexpr int kMinParallelBandwidth = 128;

} // namespace

std::vector<double> normalizedLegendre(int bandwidth, double x)
{
  checkBandwidth(bandwidth);
  x = std::clamp(x, -1.0, 1.0);
  const double s = std::sqrt(std::max(0.0, 1.0 - x * x));
  const double log_s = std::log(s); // -inf at the poles: handled below
  std::vector<double> p(legendreCount(bandwidth), 0.0);
  // log of prod_{k=1}^{m} (2k-1)/(2k), accumulated as m grows.
  double log_ratio = 0.0;
  for (int m = 0; m < bandwidth; ++m) {
    if (m > 0)
      log_ratio += std::log((2.0 * m - 1.0) / (2.0 * m));
    // Pbar_m^m = (-1)^m sqrt((2m+1)/4pi) sqrt(prod (2k-1)/2k) s^m, in log space so that
    // large m underflows cleanly to 0 instead of losing precision.
    double pmm;
    if (m == 0)
      pmm = std::sqrt(1.0 / (4.0 * M_PI));
    else if (s == 0.0)
      pmm = 0.0;
    else
      pmm = std::exp(0.5 * std::log((2.0 * m + 1.0) / (4.0 * M_PI)) + 0.5 * log_ratio +
                     m * log_s);
    if (m % 2 == 1)
      pmm = -pmm;
    p[legendreIndex(m, m, bandwidth)] = pmm;
    if (m + 1 >= bandwidth)
      continue;
    double prev2 = pmm;
    double prev1 = std::sqrt(2.0 * m + 3.0) * x * pmm;
    p[legendreIndex(m + 1, m, bandwidth)] = prev1;
    for (int l = m + 2; l < bandwidth; ++l) {
      const double ll = static_cast<double>(l) * l;
      const double mm = static_cast<double>(m) * m;
      const double a = std::sqrt((4.0 * ll - 1.0) / (ll - mm));
      const double lm1 = l - 1.0;
      const double b = std::sqrt((lm1 * lm1 - mm) / (4.0 * lm1 * lm1 - 1.0));
      const double cur = a * (x * prev1 - b * prev2);
      p[legendreIndex(l, m, bandwidth)] = cur;
      prev2 = prev1;
      prev1 = cur;
    }
  }
  return p;
}

double spectrumSquaredNorm(const SphericalSpectrum& F)
{
  double sum = 0.0;
  for (Eigen::Index m = 0; m < F.cols(); ++m)
    for (Eigen::Index l = m; l < F.rows(); ++l)
      sum += (m == 0 ? 1.0 : 2.0) * std::norm(F(l, m));
  return sum;
}

/** One r2c (forward) and one c2r (inverse) plan over all 2B rings at once. */
struct SphericalHarmonicTransform::Plans {
  detail::FftwPlan rings_r2c;
  detail::FftwPlan rings_c2r;
};

std::shared_ptr<const SphericalHarmonicTransform>
SphericalHarmonicTransform::instance(int bandwidth)
{
  checkBandwidth(bandwidth);
  static detail::InstanceCache<int, SphericalHarmonicTransform> cache;
  return cache.get(bandwidth, [bandwidth] {
    return std::make_shared<const SphericalHarmonicTransform>(bandwidth);
  });
}

SphericalHarmonicTransform::SphericalHarmonicTransform(int bandwidth)
    : bandwidth_(bandwidth)
    , plans_(std::make_unique<Plans>())
{
  checkBandwidth(bandwidth);
  const int B = bandwidth;
  const int n = 2 * B;
  weights_ = quadratureWeights(B);
  // Only the northern rings: the southern ones follow from P(-x) = (-1)^(l+m) P(x).
  legendre_.assign(static_cast<std::size_t>(legendreCount(B)) * B, 0.0);
  for (int j = 0; j < B; ++j) {
    const std::vector<double> p = normalizedLegendre(B, std::cos(ringColatitude(j, B)));
    for (int i = 0; i < legendreCount(B); ++i)
      legendre_[static_cast<std::size_t>(i) * B + j] = p[i];
  }
  auto real = detail::fftwAllocate<double>(static_cast<std::size_t>(n) * n);
  auto spec = detail::fftwAllocate<fftw_complex>(static_cast<std::size_t>(n) * (B + 1));
  std::lock_guard<std::mutex> lock(detail::fftwPlannerMutex());
  plans_->rings_r2c = detail::FftwPlan(
      fftw_plan_many_dft_r2c(1, &n, n, real.get(), nullptr, 1, n, spec.get(), nullptr,
                             1, B + 1, detail::kFftwFlags));
  plans_->rings_c2r = detail::FftwPlan(
      fftw_plan_many_dft_c2r(1, &n, n, spec.get(), nullptr, 1, B + 1, real.get(),
                             nullptr, 1, n, detail::kFftwFlags));
}

SphericalHarmonicTransform::~SphericalHarmonicTransform() = default;

SphericalSpectrum SphericalHarmonicTransform::forward(const double* samples,
                                                      int num_threads) const
{
  const int B = bandwidth_;
  const int n = 2 * B;
  const std::size_t nh = B + 1;
  auto real = detail::fftwAllocate<double>(static_cast<std::size_t>(n) * n);
  auto spec = detail::fftwAllocate<fftw_complex>(n * nh);
  std::memcpy(real.get(), samples, sizeof(double) * n * n);
  fftw_execute_dft_r2c(plans_->rings_r2c.get(), real.get(), spec.get());
  const Complex* ring = reinterpret_cast<const Complex*>(spec.get());

  SphericalSpectrum F = SphericalSpectrum::Zero(B, B);
  const double scale = M_PI / B;
  const int threads = B < kMinParallelBandwidth ? 1 : std::max(1, num_threads);
  detail::parallelFor(
      B, 1, threads, [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
        std::vector<Complex> even(B), odd(B);
        for (int m = static_cast<int>(first); m < last; ++m) {
          // Fold northern and southern rings: each degree is one dot product.
          for (int j = 0; j < B; ++j) {
            const Complex north = ring[j * nh + m];
            const Complex south = ring[(n - 1 - j) * nh + m];
            even[j] = weights_[j] * (north + south);
            odd[j] = weights_[j] * (north - south);
          }
          for (int l = m; l < B; ++l) {
            const double* p =
                &legendre_[static_cast<std::size_t>(legendreIndex(l, m, B)) * B];
            const std::vector<Complex>& folded = ((l + m) % 2 == 0) ? even : odd;
            Complex acc = 0.0;
            for (int j = 0; j < B; ++j)
              acc += p[j] * folded[j];
            F(l, m) = scale * acc;
          }
        }
      });
  return F;
}

std::vector<double>
SphericalHarmonicTransform::inverse(const SphericalSpectrum& F) const
{
  const int B = bandwidth_;
  const int n = 2 * B;
  const std::size_t nh = B + 1;
  if (F.rows() != B || F.cols() != B)
    throw InvalidArgument("inverse SHT: spectrum must be B x B");
  auto real = detail::fftwAllocate<double>(static_cast<std::size_t>(n) * n);
  auto spec = detail::fftwAllocate<fftw_complex>(n * nh);
  Complex* ring = reinterpret_cast<Complex*>(spec.get());
  for (int j = 0; j < B; ++j) {
    for (std::size_t m = 0; m < nh; ++m)
      ring[j * nh + m] = ring[(n - 1 - j) * nh + m] = 0.0;
    for (int m = 0; m < B; ++m) {
      Complex north = 0.0, south = 0.0;
      for (int l = m; l < B; ++l) {
        const Complex v =
            F(l, m) *
            legendre_[static_cast<std::size_t>(legendreIndex(l, m, B)) * B + j];
        north += v;
        south += ((l + m) % 2 == 0) ? v : -v;
      }
      ring[j * nh + m] = north;
      ring[(n - 1 - j) * nh + m] = south;
    }
  }
  fftw_execute_dft_c2r(plans_->rings_c2r.get(), spec.get(), real.get());
  return std::vector<double>(real.get(), real.get() + static_cast<std::size_t>(n) * n);
}

} // namespace pcl::phaser
