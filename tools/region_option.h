/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The --region X,Y,Z,R option of pcl_phaser_align and pcl_phaser_batch.
 */
#pragma once

#include <pcl_phaser/core/parameters.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

namespace pcl {
namespace phaser {

/** \brief X,Y,Z,R (meters, the target's frame) of a position prior, each finite and in
 *  the range of its PhaserParameters field and R > 0; empty when \a text is not. */
inline std::optional<std::array<double, 4>> parseRegion(const std::string& text)
{
  static const char* const fields[4] = {"region_x", "region_y", "region_z",
                                        "region_radius"};
  std::array<double, 4> region{};
  const char* p = text.c_str();
  for (int k = 0; k < 4; ++k) {
    char* end = nullptr;
    region[k] = std::strtod(p, &end);
    const ParameterRange* range = findParameterRange(fields[k]);
    const bool last = k == 3;
    if (end == p || *end != (last ? '\0' : ',') || !std::isfinite(region[k]) ||
        region[k] < range->min || region[k] > range->max ||
        (last && !(region[k] > 0.0)))
      return std::nullopt;
    p = end + 1;
  }
  return region;
}

/** \brief The usage message of an invalid --region \a text. */
inline std::string regionUsage(const std::string& text)
{
  char max[32];
  std::snprintf(max, sizeof(max), "%g", findParameterRange("region_radius")->max);
  return "Invalid --region '" + text +
         "': expected X,Y,Z,R in meters in the target's frame, coordinates within 1e6 "
         "m and 0 < R <= " +
         max;
}

/** \brief Set the position prior of \a p to \a region (X, Y, Z, R). */
inline void setRegion(PhaserParameters& p, const std::array<double, 4>& region)
{
  p.region = Region{region[0], region[1], region[2], region[3]};
}

} // namespace phaser
} // namespace pcl
