/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: pass 1, the global search (global_search.cpp).
#include "pipeline/stage_state.h"

namespace pcl::phaser::detail {

/** Pass 1 (global_search.cpp): all hypotheses translated, verified, refined; the best.
 */
GlobalSearch globalSearch(const SourceContext& source,
                          const So3CorrelationGrid& correlation, double source_norm,
                          StageTimes& times);

} // namespace pcl::phaser::detail
