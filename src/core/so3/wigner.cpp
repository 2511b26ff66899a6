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

WignerStep wignerStep(int l, int mp, int m)
{
  if (l == 0) // only m = m' = 0: d^1_00 = cos(beta)
    return {1.0, 0.0, 0.0};
  const double l1 = l + 1.0;
  const double mm = static_cast<double>(m) * m;
  const double mpmp = static_cast<double>(mp) * mp;
  const double r = std::sqrt((l1 * l1 - mm) * (l1 * l1 - mpmp));
  const double a = l1 * (2.0 * l + 1.0) / r;
  const double cc = -static_cast<double>(m) * mp / (static_cast<double>(l) * l1);
  const double ll = static_cast<double>(l) * l;
  const double b = l1 * std::sqrt(std::max(0.0, (ll - mm) * (ll - mpmp))) / (l * r);
  return {a, a * cc, b};
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

std::vector<double> wignerSmallD(int mp, int m, int bandwidth, double beta)
{
  checkBandwidth(bandwidth);
  std::vector<double> d(bandwidth, 0.0);
  const int L = std::max(std::abs(mp), std::abs(m));
  if (L >= bandwidth)
    return d;
  const std::vector<double> lf = logFactorials(2 * L + 1);
  const WignerStart start = wignerStart(mp, m, lf);
  const double cb = std::cos(beta);
  double prev =
      start.value(std::log(std::cos(0.5 * beta)), std::log(std::sin(0.5 * beta)));
  double prev2 = 0.0;
  for (int l = L; l < bandwidth; ++l) {
    d[l] = prev;
    const WignerStep st = wignerStep(l, mp, m);
    const double next = (st.a * cb + st.ac) * prev - st.b * prev2;
    prev2 = prev;
    prev = next;
  }
  return d;
}

} // namespace pcl::phaser
