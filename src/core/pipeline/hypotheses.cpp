/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Pass 1: the hypotheses, their translations, and the choice among them, widened when
 * it would not be claimed.
 */
#include "pipeline/hypotheses.h"
#include "pipeline/rotation_search.h"
#include "pipeline/stage_tasks.h"
#include "pipeline/translation_search.h"
#include "pipeline/verdict.h"

#include <algorithm>

namespace pcl::phaser::detail {
namespace {

/** Inlier share one hypothesis at least must reach for verification to rank them. */
constexpr double kMinRankingInliers = 0.1;
/** Hypotheses with at least this share of the most inliers rank above the others. */
constexpr double kMinSupport = 0.5;

/** By \a support of inliers, then rank (no limits: pass-1 figures are not final). */
bool ranksAbove(const Verification& a, const Verification& b, double support)
{
  const bool a_supported = a.inlier_fraction >= support;
  if (a_supported != (b.inlier_fraction >= support))
    return a_supported;
  return a.rank > b.rank;
}

/** The best verified hypothesis if poses can be verified, else the most overlapping. */
void chooseHypothesis(const SourceContext& source, GlobalSearch& search)
{
  const std::vector<Hypothesis>& hypotheses = search.hypotheses;
  bool verifiable = false;
  double most_inliers = 0.0;
  for (const Hypothesis& h : hypotheses) {
    verifiable = verifiable || h.verification.inlier_fraction >= kMinRankingInliers;
    most_inliers = std::max(most_inliers, h.verification.inlier_fraction);
  }
  verifiable = verifiable && source.canVerify();
  std::size_t best = 0;
  for (std::size_t k = 1; k < hypotheses.size(); ++k) {
    const Hypothesis& h = hypotheses[k];
    const bool better =
        verifiable ? ranksAbove(h.verification, hypotheses[best].verification,
                                kMinSupport * most_inliers)
                   : !h.from_orientation && h.overlap > hypotheses[best].overlap;
    if (better)
      best = k;
  }
  search.chosen = static_cast<int>(best);
  search.pose = Pose();
  search.pose.R = hypotheses[best].rotation;
  search.pose.t = hypotheses[best].translation;
  search.pose.verification = hypotheses[best].verification;
  search.pose.verifiable = verifiable;
}

} // namespace

// When the choice would not be claimed (it misses the limits or does not stand out),
// the spare orientation and more translation peaks join and it is made again.
GlobalSearch globalSearch(const SourceContext& source, StageTimes& times)
{
  RotationHypotheses rotations = rotationSearch(source, times);
  GlobalSearch search;
  search.hypotheses = std::move(rotations.hypotheses);
  std::vector<Eigen::Matrix3d> unrefined;
  for (const Hypothesis& h : search.hypotheses)
    unrefined.push_back(h.rotation);
  translateHypotheses(source, search.hypotheses, times);
  chooseHypothesis(source, search);
  const auto start = Clock::now();
  const bool widen = source.canVerify() &&
                     (!meetsLimits(search.pose.verification, source.settings.limits) ||
                      !standsOut(source, search.pose, search.hypotheses).stands_out);
  times.verification += msSince(start);
  search.decided = search.pose.verifiable && !widen;
  if (widen) {
    const std::size_t first = search.hypotheses.size();
    search.hypotheses.insert(search.hypotheses.end(), rotations.spare.begin(),
                             rotations.spare.end());
    translateHypotheses(source, search.hypotheses, times, first);
    addTranslationPeaks(source, unrefined, search.hypotheses, times);
    chooseHypothesis(source, search);
  }
  return search;
}

} // namespace pcl::phaser::detail
