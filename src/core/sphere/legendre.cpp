/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "sphere/legendre.h"
#include "support/error.h"

#include <algorithm>
#include <cmath>

namespace pcl::phaser {

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

} // namespace pcl::phaser
