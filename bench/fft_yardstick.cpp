/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "fft_yardstick.h"

#include <fftw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

namespace pcl::phaser {
namespace bench {

double fftYardstickMs()
{
  constexpr int n = 128;
  const std::size_t real_size = std::size_t(n) * n * n;
  double* in = fftw_alloc_real(real_size);
  fftw_complex* out = fftw_alloc_complex(std::size_t(n) * n * (n / 2 + 1));
  fftw_plan plan = fftw_plan_dft_r2c_3d(n, n, n, in, out, FFTW_MEASURE);
  for (std::size_t i = 0; i < real_size; ++i) // FFTW_MEASURE overwrote the input
    in[i] = std::sin(0.001 * static_cast<double>(i));
  std::vector<double> ms;
  for (int k = 0; k < 15; ++k) {
    const auto start = std::chrono::steady_clock::now();
    fftw_execute(plan);
    ms.push_back(std::chrono::duration<double, std::milli>(
                     std::chrono::steady_clock::now() - start)
                     .count());
  }
  fftw_destroy_plan(plan);
  fftw_free(out);
  fftw_free(in);
  fftw_forget_wisdom();
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return ms[ms.size() / 2];
}

} // namespace bench
} // namespace pcl::phaser
