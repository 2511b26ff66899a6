/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: the rotation hypotheses of pass 1 (rotation_search.cpp).
#include "pipeline/source_context.h"

#include <pcl_phaser/core/result.h>

#include <vector>

namespace pcl::phaser::detail {

/** The rotations pass 1 tries, not yet translated. */
struct RotationHypotheses {
  /** The peaks of the range correlation, of the occupancy magnitudes (objects) and the
   *  first orientation-histogram peaks (StageSettings::params.orientation_candidates).
   */
  std::vector<Hypothesis> hypotheses;
  /** The next orientation-histogram peaks, tried when the choice is not claimed. */
  std::vector<Hypothesis> spare;
};

/** The source's spherical spectrum correlated with the target's on the rows the priors
 *  allow, and the rotation hypotheses of its peaks and of the other correlations.
 *  \throws InvalidArgument when the source carries no spherical signal */
RotationHypotheses rotationSearch(const SourceContext& source, StageTimes& times);

} // namespace pcl::phaser::detail
