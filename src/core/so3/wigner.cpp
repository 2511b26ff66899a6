/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "so3/wigner.h"
#include "support/error.h"
#include "support/instance_cache.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace pcl::phaser {

std::vector<double> logFactorials(int n)
{
  std::vector<double> lf(std::max(n, 0) + 1, 0.0);
  for (int i = 2; i <= n; ++i)
    lf[i] = lf[i - 1] + std::log(static_cast<double>(i));
  return lf;
}

double WignerStart::value(double log_cos_half, double log_sin_half) const
{
  // A zero exponent contributes nothing, even where the log is -inf (beta = 0 or pi).
  double e = log_scale;
  if (exp_cos)
    e += exp_cos * log_cos_half;
  if (exp_sin)
    e += exp_sin * log_sin_half;
  return sign * std::exp(e);
}

WignerStart wignerStart(int mp, int m, const std::vector<double>& lf)
{
  const int L = std::max(std::abs(mp), std::abs(m));
  WignerStart s{L, 1.0, 0.0, 0, 0};
  auto halfLogK = [&](int k) { return 0.5 * (lf[2 * L] - lf[L + k] - lf[L - k]); };
  auto parity = [](int e) { return (std::abs(e) % 2) ? -1.0 : 1.0; };
  if (mp == L) { // (i)
    s.sign = parity(L - m);
    s.log_scale = halfLogK(m);
    s.exp_cos = L + m;
    s.exp_sin = L - m;
  } else if (mp == -L) { // (ii)
    s.log_scale = halfLogK(m);
    s.exp_cos = L - m;
    s.exp_sin = L + m;
  } else if (m == L) { // (iii)
    s.log_scale = halfLogK(mp);
    s.exp_cos = L + mp;
    s.exp_sin = L - mp;
  } else { // (iv) m == -L
    s.sign = parity(L + mp);
    s.log_scale = halfLogK(mp);
    s.exp_cos = L - mp;
    s.exp_sin = L + mp;
  }
  return s;
}

WignerStepTable::WignerStepTable(int bandwidth)
{
  checkBandwidth(bandwidth);
  const int n = bandwidth + 1;
  stride_ = static_cast<std::size_t>(n);
  root_.assign(stride_ * n, 0.0);
  inv_root_.assign(stride_ * n, 0.0);
  for (int l = 0; l < n; ++l)
    for (int m = 0; m < l; ++m) {
      root_[index(l, m)] =
          std::sqrt(static_cast<double>(l) * l - static_cast<double>(m) * m);
      inv_root_[index(l, m)] = 1.0 / root_[index(l, m)];
    }
  growth_.assign(n, 0.0);
  ratio_.assign(n, 0.0);
  inv_ll1_.assign(n, 0.0);
  for (int l = 1; l < n; ++l) {
    growth_[l] = (l + 1.0) * (2.0 * l + 1.0);
    ratio_[l] = (l + 1.0) / l;
    inv_ll1_[l] = 1.0 / (static_cast<double>(l) * (l + 1.0));
  }
}

std::shared_ptr<const WignerStepTable> wignerStepTable(int bandwidth)
{
  static detail::InstanceCache<int, WignerStepTable> cache;
  checkBandwidth(bandwidth);
  return cache.get(bandwidth,
                   [&] { return std::make_shared<const WignerStepTable>(bandwidth); });
}

} // namespace pcl::phaser
