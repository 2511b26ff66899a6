/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "verification/ranking.h"

#include <algorithm>

namespace pcl::phaser {

Verification ranked(const Verification& measured)
{
  Verification out = measured;
  out.rank =
      measured.score - kViolationWeight * (measured.free_space_violation +
                                           measured.reverse_free_space_violation);
  return out;
}

bool meetsLimits(const Verification& verification, const VerificationLimits& limits)
{
  return verification.inlier_fraction >= limits.min_inlier_fraction &&
         verification.constraint >= limits.min_constraint &&
         std::max(verification.free_space_violation,
                  verification.reverse_free_space_violation) <=
             limits.max_free_space_violation;
}

} // namespace pcl::phaser
