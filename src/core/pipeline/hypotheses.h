/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: pass 1, the hypotheses and the choice among them
// (hypotheses.cpp).
#include "pipeline/pose.h"

#include <vector>

namespace pcl::phaser::detail {

/** What pass 1 found: every hypothesis, verified, and the one chosen with its pose. */
struct GlobalSearch {
  std::vector<Hypothesis> hypotheses;
  int chosen = 0;
  Pose pose;
  /** The first choice was verified, within the limits and distinct: the later passes
   *  and the rotation refinement are skipped (they change such a pose by hundredths of
   *  a degree, if at all). */
  bool decided = false;
};

/** Pass 1: the rotation hypotheses (rotationSearch) translated, verified and refined,
 *  and the best; when that one would not be claimed, with the spare orientation peaks
 *  and more translation peaks.
 *  \throws InvalidArgument when the source carries no spherical signal */
GlobalSearch globalSearch(const SourceContext& source, StageTimes& times);

} // namespace pcl::phaser::detail
