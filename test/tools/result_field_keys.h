/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The keys of visitResultFields() that pcl_phaser_align --json and the batch's records
 * both write, in order: pinned here, so that a rename is a decision of both tools.
 */
#pragma once

#include <array>

namespace pcl::phaser::test {

/** \brief The shared result keys (after transformation and converged). */
constexpr std::array<const char*, 18> kResultFieldKeys = {
    "covariance",
    "rotation_score",
    "translation_score",
    "normalized_overlap",
    "inlier_fraction",
    "verification_score",
    "free_space_violation",
    "reverse_free_space_violation",
    "constraint",
    "verification_rank",
    "runner_up_rank",
    "runner_up_error",
    "verification_radius",
    "verification_samples",
    "verified",
    "refusal",
    "passes",
    "stages_ms"};

/** \brief The members of "stages_ms": milliseconds per stage. */
constexpr std::array<const char*, 8> kStageKeys = {
    "target",     "sampling",    "sht",         "so3",
    "refinement", "translation", "orientation", "verification"};

} // namespace pcl::phaser::test
