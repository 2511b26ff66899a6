// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file statistics.h
 * \brief The median and quantiles of the tools' and the benchmark's reports.
 */
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace pcl {
namespace phaser {

/** \brief The \a q quantile (0..1, linear between ranks) of \a values; NaN when empty.
 */
inline double quantile(std::vector<double> values, double q)
{
  if (values.empty())
    return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const double rank = q * static_cast<double>(values.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(rank));
  const auto hi = std::min(values.size() - 1, lo + 1);
  const double w = rank - static_cast<double>(lo);
  return (1.0 - w) * values[lo] + w * values[hi];
}

/** \brief The median of \a values (the mean of the middle two for an even count); NaN
 *  when empty. */
inline double median(std::vector<double> values)
{
  return quantile(std::move(values), 0.5);
}

} // namespace phaser
} // namespace pcl
