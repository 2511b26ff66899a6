/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Internal to pcl_phaser_bench revisits (revisits.cpp): a trial, the distance bins, and
 * the covariance calibration (revisits_calibration.cpp): the NEES table and the
 * odometry drift of the references.
 */
#pragma once

#include "methods.h"
#include "revisits.h"

#include <Eigen/Core>

#include <ostream>
#include <string>
#include <vector>

namespace pcl::phaser {
namespace bench {

constexpr double kRreThreshold = 5.0;  ///< deg, both success levels
constexpr double kRteThresholdA = 2.0; ///< m, loop-closure level
constexpr double kRteThresholdB = 0.6; ///< m, the benchmark's usual level

/** A range of the distance between the scans, [lo, hi). */
struct Bin {
  std::string label;
  double lo, hi;
};

/** One method on one pair; success: @2 m (RRE < kRreThreshold, RTE < kRteThresholdA).
 */
struct RevisitTrial : Judged {
  RevisitPair pair;

  /** \brief Success @0.6 m: RTE < kRteThresholdB. */
  bool successB() const { return rre < kRreThreshold && rte < kRteThresholdB; }
  /** \brief Whether this is a trial of \a name on a pair whose distance is in \a bin.
   */
  bool in(const std::string& name, const Bin& bin) const
  {
    return method == name && pair.dist >= bin.lo && pair.dist < bin.hi;
  }
};

/** \brief The distance bins of the tables: four disjoint ones, then <10 m, >=10 m, all.
 */
const std::vector<Bin>& bins();

/** \brief Writes a Markdown table: the header "| method | distance | " and \a columns,
 *  then \a row(method, bin) for every method and distance bin, in that order. */
template <typename Row>
void writeRows(std::ostream& out, const std::vector<const char*>& columns,
               const std::vector<std::string>& methods, const Row& row)
{
  out << "| method | distance |";
  for (const char* column : columns)
    out << ' ' << column << " |";
  out << "\n|---|---|";
  for (std::size_t k = 0; k < columns.size(); ++k)
    out << "---|";
  out << '\n';
  for (const std::string& method : methods)
    for (const Bin& bin : bins())
      row(method, bin);
}

/** \brief The covariance's calibration per method (those with one) and distance bin:
 *  converged trials, mean and median 6-D NEES, the shares inside the 95 % ellipsoids
 *  (6-D, and each block in 3-D), mean NEES per block, RMS errors, median sigmas. */
void writeNeesTable(std::ostream& out, const std::vector<RevisitTrial>& trials,
                    const std::vector<std::string>& methods);

/** \brief The reference poses of \a pairs corrected for a linear odometry drift
 *  (correctDrift(), m per scan index, world frame), said in \a origin; false (with a
 *  message) when a pair's scans have no pose. */
bool correctReferences(const Eigen::Vector3d& drift, const std::vector<ScanPose>& poses,
                       std::vector<RevisitPair>& pairs, std::string& origin);

/** \brief "Linear odometry drift ... fitted" (fitDrift()) on the converged trials of
 *  \a method, or "" without any or without poses. */
std::string driftLine(const std::vector<RevisitTrial>& trials,
                      const std::string& method, const std::vector<ScanPose>& poses);

} // namespace bench
} // namespace pcl::phaser
