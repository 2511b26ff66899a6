/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: translations by occupancy correlation, and those of pass 1's
// hypotheses (translation_search.cpp).
#include "pipeline/source_context.h"

#include <pcl_phaser/core/result.h>

#include <limits>
#include <vector>

namespace pcl::phaser::detail {

/** Translation of \a points onto \a target at the whitened correlation's sub-voxel
 *  peak, no longer than \a max_shift meters; with \a volume the plain correlation kept
 *  and the sidelobe score computed; the source's spectrum energy into \a source_energy
 *  if given. */
SpatialCorrelationResult
correlateTranslation(const SpatialSpectrum& target, const Eigen::Matrix3Xd& points,
                     double whitening, int num_threads, StageTimes& times,
                     SpatialVolume* volume = nullptr, double* source_energy = nullptr,
                     double max_shift = std::numeric_limits<double>::infinity());

/** Hypotheses from \a first on translated on the coarse grid within the priors' shift
 *  bound, verified and (where the source can be verified; before it the right one often
 *  ranks low) refined on the samples. */
void translateHypotheses(const SourceContext& source,
                         std::vector<Hypothesis>& hypotheses, StageTimes& times,
                         std::size_t first = 0);

/** More translation peaks per rotation of \a rotations (\a hypotheses' first ones,
 *  before their refinement), verified and refined, appended to \a hypotheses: on
 *  partial views the highest can be off. */
void addTranslationPeaks(const SourceContext& source,
                         const std::vector<Eigen::Matrix3d>& rotations,
                         std::vector<Hypothesis>& hypotheses, StageTimes& times);

} // namespace pcl::phaser::detail
