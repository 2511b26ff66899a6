/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_bench revisits: the distance bins, and how the covariance of the converged
 * trials covers their errors (the NEES table), against references corrected for the
 * odometry's drift or not.
 */
#include "protocol.h"
#include "report.h"
#include "revisits_calibration.h"

#include <pcl/console/print.h>

#include <cmath>
#include <limits>

namespace pcl::phaser {
namespace bench {

const std::vector<Bin>& bins()
{
  constexpr double inf = std::numeric_limits<double>::infinity();
  static const std::vector<Bin> all = {
      {"[0, 5) m", 0.0, 5.0},     {"[5, 10) m", 5.0, 10.0}, {"[10, 15) m", 10.0, 15.0},
      {"[15, inf) m", 15.0, inf}, {"<10 m", 0.0, 10.0},     {">=10 m", 10.0, inf},
      {"all", 0.0, inf}};
  return all;
}

void writeNeesTable(std::ostream& out, const std::vector<RevisitTrial>& trials,
                    const std::vector<std::string>& methods)
{
  out << '\n';
  writeRows(out,
            {"converged with covariance", "mean NEES (6)", "median NEES",
             "inside 95 % (6-D, 12.59)", "inside 95 % rot. / trans. (3-D, 7.81)",
             "mean NEES rot. / trans. (3)", "RMS RRE (deg)", "RMS RTE (m)",
             "median sigma_rot (deg)", "median sigma_trans (m)"},
            methods, [&](const std::string& method, const Bin& bin) {
              const NeesSummary s = summarizeNees(select(
                  trials, [&](const RevisitTrial& t) { return t.in(method, bin); }));
              if (s.n == 0)
                return;
              const auto share = [&](int k) {
                return formatValue("%.1f %%", 100.0 * k / s.n);
              };
              out << "| " << method << " | " << bin.label << " | " << s.n << " | "
                  << formatValue("%.2f", s.mean) << " | "
                  << formatValue("%.2f", s.median) << " | " << share(s.inside) << " | "
                  << share(s.inside_rot) << " / " << share(s.inside_trans) << " | "
                  << formatValue("%.2f", s.mean_rot) << " / "
                  << formatValue("%.2f", s.mean_trans) << " | "
                  << formatValue("%.3f", s.rms_rre) << " | "
                  << formatValue("%.3f", s.rms_rte) << " | "
                  << formatValue("%.3f", s.sigma_rot) << " | "
                  << formatValue("%.3f", s.sigma_trans) << " |\n";
            });
}

/** The reference poses of \a pairs corrected for the drift of -reference-drift; false
 *  (with a message) when a pair's scans have no pose. */
bool correctReferences(const Eigen::Vector3d& drift, const std::vector<ScanPose>& poses,
                       std::vector<RevisitPair>& pairs, std::string& origin)
{
  for (RevisitPair& pair : pairs)
    if (!correctDrift(pair, poses, drift)) {
      pcl::console::print_error("revisits: no odometry pose for %s -> %s\n",
                                pair.source.c_str(), pair.target.c_str());
      return false;
    }
  origin += "; reference poses corrected for a linear odometry drift of (" +
            formatValue("%.4g", drift.x()) + ", " + formatValue("%.4g", drift.y()) +
            ", " + formatValue("%.4g", drift.z()) + ") m per scan index";
  return true;
}

/** "Odometry drift fitted ..." for the converged trials of \a method (fitDrift()). */
std::string driftLine(const std::vector<RevisitTrial>& trials,
                      const std::string& method, const std::vector<ScanPose>& poses)
{
  std::vector<RevisitPair> pairs;
  std::vector<Eigen::Matrix4d> estimates;
  for (const RevisitTrial& t : trials)
    if (t.method == method && t.converged) {
      pairs.push_back(t.pair);
      estimates.push_back(t.estimate);
    }
  if (pairs.empty() || poses.empty())
    return "";
  const Eigen::Vector3d d = fitDrift(pairs, estimates, poses);
  return "Linear odometry drift of the reference poses that best explains the "
         "translation errors of the " +
         std::to_string(pairs.size()) + " converged " + method +
         " trials (fitDrift(), world frame): (" + formatValue("%.4g", d.x()) + ", " +
         formatValue("%.4g", d.y()) + ", " + formatValue("%.4g", d.z()) +
         ") m per scan index, " + formatValue("%.3f", 174.0 * d.norm()) +
         " m over scans 0-174 (pass it as --reference-drift DX,DY,DZ to judge against "
         "corrected references).\n";
}

} // namespace bench
} // namespace pcl::phaser
