/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace pcl::phaser {

/** \brief log(i!) for i = 0..n (no std::lgamma: it may write the global signgam). */
std::vector<double> logFactorials(int n);

/** \brief First value d^L_{m'm}(beta) of the l-recurrence, L = max(|m'|, |m|), in log
 *  space: sign exp(log_scale + exp_cos log cos(beta/2) + exp_sin log sin(beta/2)). */
struct WignerStart {
  int degree;       ///< L
  double sign;      ///< +1 or -1
  double log_scale; ///< 0.5 log K(L, k)
  int exp_cos;      ///< power of cos(beta/2)
  int exp_sin;      ///< power of sin(beta/2)

  /** \brief Value at beta given log cos(beta/2) and log sin(beta/2) (may be -inf). */
  double value(double log_cos_half, double log_sin_half) const;
};

/** \brief The start of the l-recurrence for the orders (m' = \a mp, \a m).
 *  \param[in] log_factorials table of at least 2 max(|m'|,|m|) + 1 entries */
WignerStart wignerStart(int mp, int m, const std::vector<double>& log_factorials);

/** \brief Coefficients of one step of the Kostelec-Rockmore recurrence in l:
 *  d^{l+1} = (a cos(beta) + ac) d^l - b d^{l-1}. */
struct WignerStep {
  double a, ac, b;
};

/** \brief The recurrence's steps from tables of sqrt(l^2 - m^2) and their inverses: a
 *  few products per step instead of two square roots and three divisions. */
class WignerStepTable {
public:
  /** \param[in] bandwidth B: steps for l < B, |m|, |m'| < B */
  explicit WignerStepTable(int bandwidth);
  WignerStep step(int l, int mp, int m) const
  {
    if (l == 0)
      return {1.0, 0.0, 0.0};
    const int am = m < 0 ? -m : m, amp = mp < 0 ? -mp : mp;
    const double inv_r = inv_root_[index(l + 1, am)] * inv_root_[index(l + 1, amp)];
    const double a = growth_[l] * inv_r;
    return {a, -a * m * mp * inv_ll1_[l],
            ratio_[l] * root_[index(l, am)] * root_[index(l, amp)] * inv_r};
  }

private:
  std::size_t index(int l, int m) const
  {
    return static_cast<std::size_t>(l) * stride_ + static_cast<std::size_t>(m);
  }
  std::size_t stride_;
  std::vector<double> root_, inv_root_; ///< sqrt(l^2 - m^2) and 1 / it, 0 <= m <= l
  std::vector<double> growth_, ratio_, inv_ll1_; ///< (l+1)(2l+1), (l+1)/l, 1/(l(l+1))
};

/** \brief The step table of bandwidth B, built once per process and shared.
 *  \throws InvalidArgument for a bandwidth outside [1, 256] */
std::shared_ptr<const WignerStepTable> wignerStepTable(int bandwidth);

} // namespace pcl::phaser
