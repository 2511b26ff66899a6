/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "support/error.h"

#include <pcl_phaser/core/parameters.h>

#include <algorithm>
#include <cmath>
#include <omp.h>
#include <sstream>

namespace pcl::phaser {

static_assert(kParameterRanges[0].max == kMaxBandwidth, "bandwidth range");

const ParameterRange* findParameterRange(const std::string& name)
{
  for (const ParameterRange& r : kParameterRanges)
    if (name == r.name)
      return &r;
  return nullptr;
}

std::string validateParameters(const PhaserParameters& p)
{
  for (const ParameterRange& r : kParameterRanges) {
    const double v = r.value(p);
    if ((v >= r.min && v <= r.max && std::isfinite(v)) ||
        (r.integer == &PhaserParameters::spatial_grid_size && p.voxel_size > 0.0))
      continue;
    std::ostringstream out;
    out << r.name << " = " << v << " is outside its range " << r.min << ".." << r.max
        << " (" << r.meaning << ")";
    return out.str();
  }
  if (p.region && !(p.region->radius > 0.0))
    return "region_radius = 0 with a region: a position prior needs a radius > 0 m";
  return {};
}

int resolveThreadCount(int num_threads)
{
  return num_threads > 0 ? num_threads : std::clamp(omp_get_num_procs(), 1, 64);
}

} // namespace pcl::phaser
