/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_bench revisits: each pair of lidar/balm_handheld/pairs.txt ("source target
 * dist_m rel_rot_deg overlap" then T_target_source row-major 4 x 4) by each method, run
 * as the compare study runs them; success at 2 m and at 0.6 m (RRE < 5 deg both), by
 * bins of the distance between the scans, with the converged flag's false accepts and
 * the times in units of one 128^3 FFT, and by stage. With --derived-pairs the pairs are
 * derived from poses_T_world_lidar.txt instead (derivePairs() in revisits.h). How the
 * covariance of the converged trials covers their errors (the NEES table), against
 * references corrected for the odometry's drift or not.
 */
#include "cloud_reading.h"
#include "fft_yardstick.h"
#include "methods.h"
#include "protocol.h"
#include "report.h"
#include "result_csv.h"
#include "revisits.h"
#include "subcommands.h"

#include <pcl/console/print.h>
#include <pcl/filters/filter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace pcl::phaser {
namespace bench {

namespace {

namespace console = pcl::console;

const char* const kFolder = "lidar/balm_handheld";

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

/** The distance bins of the tables: four disjoint ones, then <10 m, >=10 m, all. */
const std::vector<Bin>& bins()
{
  constexpr double inf = std::numeric_limits<double>::infinity();
  static const std::vector<Bin> all = {
      {"[0, 5) m", 0.0, 5.0},     {"[5, 10) m", 5.0, 10.0}, {"[10, 15) m", 10.0, 15.0},
      {"[15, inf) m", 15.0, inf}, {"<10 m", 0.0, 10.0},     {">=10 m", 10.0, inf},
      {"all", 0.0, inf}};
  return all;
}

/** \brief Writes a Markdown table: the header "| method | distance | " and \a columns,
 *  then \a row(method, bin) for every method and distance bin, in that order. */
template <typename Row>
void writeRows(std::ostream& out, std::vector<std::string> columns,
               const std::vector<std::string>& methods, const Row& row)
{
  columns.insert(columns.begin(), {"method", "distance"});
  out << tableHeader(columns);
  for (const std::string& method : methods)
    for (const Bin& bin : bins())
      row(method, bin);
}

/** The covariance's calibration per method (those with one) and distance bin:
 *  converged trials, mean and median 6-D NEES, the shares inside the 95 % ellipsoids
 *  (6-D, and each block in 3-D), mean NEES per block, RMS errors, median sigmas. */
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

/** The study's options; voxel: 1 m by default, as for the compare study's LiDAR. */
struct RevisitOptions : StudyOptions {
  std::string pairs_file; ///< empty: <data>/lidar/balm_handheld/pairs.txt
  int max_pairs = 0;
  int derived_pairs = 0; ///< per bin from the poses instead of the pairs file; 0: off
  double source_wedge = 1.0; ///< azimuth share of each source kept (--source-wedge)
  /** --reference-drift: linear odometry drift (world, m per scan index) removed from
   *  the reference poses (correctDrift()); empty: none */
  std::vector<double> drift;
};

constexpr std::size_t kDisjointBins = 4; ///< the first bins() partition the distances

/** Reads and checks the options; false when one is invalid (recorded in \a args). */
bool parseRevisitOptions(BenchArguments& args, RevisitOptions& o)
{
  readStudyOptions(args, o, {"phaser", "phaser_xyz", "sacia", "prerejective"}, 1.0);
  o.pairs_file = args.text("--pairs-file");
  o.max_pairs = static_cast<int>(args.integer("--max-pairs", 0));
  o.source_wedge = args.number("--source-wedge", 1.0);
  o.derived_pairs = static_cast<int>(args.integer("--derived-pairs", 0));
  o.drift = args.numbers("--reference-drift", {});
  checkStudyOptions(args, o, true);
  args.check(o.max_pairs >= 0, "--max-pairs: >= 0");
  args.check(o.derived_pairs >= 0, "--derived-pairs: >= 0");
  args.check(o.source_wedge > 0.0 && o.source_wedge <= 1.0,
             "--source-wedge: in (0, 1]");
  args.check(o.voxel > 0.0, "--voxel: > 0");
  args.check(o.drift.empty() || o.drift.size() == 3,
             "--reference-drift: three numbers DX,DY,DZ");
  return args.ok();
}

/** The pairs of the study: those of the pairs file or, with --derived-pairs, those
 * derivePairs() finds in the poses; \a origin says which, for the report. The poses
 * file, when present, into \a poses (the drift correction and fit use them too). False
 * (with a message) on an unreadable or malformed file. */
bool loadPairs(const RevisitOptions& o, const std::string& pairs_file,
               const std::string& poses_file, std::vector<ScanPose>& poses,
               std::vector<RevisitPair>& pairs, std::string& origin)
{
  std::string error;
  std::vector<RevisitPair> listed;
  if (!readPairs(pairs_file, listed, error) ||
      (std::filesystem::exists(poses_file) &&
       !readScanPoses(poses_file, poses, error))) {
    console::print_error("revisits: %s\n", error.c_str());
    return false;
  }
  pairs = listed;
  origin = "the pairs of " + pairs_file;
  if (o.derived_pairs == 0)
    return true;
  DerivedCounts counts;
  pairs = derivePairs(poses, listed, o.derived_pairs, o.seed, &counts);
  std::ostringstream text;
  text << pairs.size() << " pairs derived from " << poses_file << " (up to "
       << o.derived_pairs << " per bin, seed " << o.seed << ", none of " << pairs_file
       << "; taken / ordered candidates:";
  for (std::size_t b = 0; b < kDerivedBins; ++b)
    text << (b ? "," : "") << " [" << kDerivedEdges[b] << ", " << kDerivedEdges[b + 1]
         << (b + 1 == kDerivedBins ? "] m " : ") m ") << counts.chosen[b] << " / "
         << counts.candidates[b];
  origin = text.str() + ")";
  std::fprintf(stderr, "revisits: %s\n", origin.c_str());
  return true;
}

void writeCsvRow(std::ostream& out, const RevisitTrial& t)
{
  char line[512];
  std::snprintf(line, sizeof(line),
                "%s,%s,%s,%g,%g,%g,%.6f,%.6f,%d,%.3f,%.6g,%.4g,%.4g,%.4g,%.4g,%.4g",
                t.method.c_str(), t.pair.source.c_str(), t.pair.target.c_str(),
                t.pair.dist, t.pair.rel_rot, t.pair.overlap, t.rre, t.rte,
                t.converged ? 1 : 0, t.ms, t.phaser ? std::nan("") : t.score,
                t.nees.nees, t.nees.nees_rot, t.nees.nees_trans, t.nees.sigma_rot_deg,
                t.nees.sigma_trans_m);
  out << line;
  writeResultCells(out, t.phaser ? &*t.phaser : nullptr);
  out << "\n" << std::flush; // a long run can be read while it goes
}

/** The sector of \a scan that a sensor with a \a fraction x 360 deg horizontal field of
 *  view would have seen, about a direction drawn from (\a seed, \a pair). */
Cloud::ConstPtr wedgeOf(const Cloud& scan, double fraction, unsigned seed,
                        std::size_t pair)
{
  std::seed_seq seq{seed, static_cast<unsigned>(pair)};
  std::mt19937 rng(seq);
  Condition wedge;
  wedge.kind = Condition::Kind::Overlap;
  wedge.value = fraction;
  auto out = pcl::make_shared<Cloud>(scan);
  applyCondition(wedge, *out, rng);
  return out;
}

/** Every pair by every method, as Runner::run() of the compare study does it. */
std::vector<RevisitTrial> runTrials(const RevisitOptions& o, const std::string& folder,
                                    const std::vector<RevisitPair>& pairs,
                                    std::ostream* csv)
{
  // seed: + pose, which is 0 for real pairs
  const MethodSettings settings =
      studySettings(o.engine, o.voxel, o.seed, o.fpcs_seconds);
  std::map<std::string, Cloud::ConstPtr> scans; // each read once
  auto scan = [&](const std::string& name) {
    if (!scans.count(name))
      scans[name] = loadFiniteScan(
          std::filesystem::path(name).is_absolute() ? name : folder + "/" + name);
    return scans[name];
  };
  std::vector<RevisitTrial> trials;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const RevisitPair& pair = pairs[i];
    Cloud::ConstPtr source = scan(pair.source);
    const Cloud::ConstPtr target = scan(pair.target);
    if (!source || !target)
      continue; // the loader said why
    if (o.source_wedge < 1.0)
      source = wedgeOf(*source, o.source_wedge, o.seed, i);
    for (const std::string& name : o.methods) {
      RevisitTrial t;
      static_cast<Judged&>(t) =
          judge(name, findMethod(name)->run(source, target, settings), pair.truth);
      t.pair = pair;
      t.success = t.rre < kRreThreshold && t.rte < kRteThresholdA;
      std::fprintf(stderr,
                   "[%zu/%zu] %s -> %s (%.2f m) %-12s RRE %7.2f deg  RTE %7.3f m  "
                   "converged %d  %8.0f ms  NEES %.2f (rot. %.2f, trans. %.2f)\n",
                   i + 1, pairs.size(), pair.source.c_str(), pair.target.c_str(),
                   pair.dist, name.c_str(), t.rre, t.rte, t.converged ? 1 : 0, t.ms,
                   t.nees.nees, t.nees.nees_rot, t.nees.nees_trans);
      if (csv)
        writeCsvRow(*csv, t);
      trials.push_back(t);
    }
  }
  return trials;
}

/** "k / n (p %)", "-" when n is 0. */
std::string countOf(int k, int n)
{
  if (n == 0)
    return "-";
  return std::to_string(k) + " / " + std::to_string(n) + " (" +
         formatValue("%.0f %%", 100.0 * k / n) + ")";
}

/** The Summary of \a method's trials in \a bin (success @2 m), and ok_b: @0.6 m. */
struct BinSummary : Summary {
  int ok_b = 0;
};

BinSummary summarizeBin(const std::vector<RevisitTrial>& trials,
                        const std::string& method, const Bin& bin)
{
  BinSummary s;
  static_cast<Summary&>(s) = summarize(
      select(trials, [&](const RevisitTrial& t) { return t.in(method, bin); }));
  for (const RevisitTrial& t : trials)
    s.ok_b += t.in(method, bin) && t.successB();
  return s;
}

void writeTable(std::ostream& out, const std::vector<RevisitTrial>& trials,
                const std::vector<std::string>& methods, double fft_ms)
{
  writeRows(out,
            {"n", "success @2 m", "success @0.6 m", "median RRE (deg)",
             "median RTE (m)", "median time (ms)", "median time (FFT128)",
             "false accepts (converged failures)", "converged successes"},
            methods, [&](const std::string& method, const Bin& bin) {
              const BinSummary s = summarizeBin(trials, method, bin);
              out << "| " << method << " | " << bin.label << " | " << s.n << " | "
                  << formatValue("%.0f %%", s.n ? 100.0 * s.ok / s.n : NAN) << " | "
                  << formatValue("%.0f %%", s.n ? 100.0 * s.ok_b / s.n : NAN) << " | "
                  << formatValue("%.2f", s.median_rre) << " | "
                  << formatValue("%.3f", s.median_rte) << " | "
                  << formatValue("%.0f", s.median_ms) << " | "
                  << formatValue("%.1f", s.median_ms / fft_ms) << " | "
                  << countOf(s.converged_failed, s.n - s.ok) << " | "
                  << countOf(s.converged_ok, s.ok) << " |\n";
            });
}

/** DIR/revisits_success.{dat,gp} and, with gnuplot, the PNG; returns the PNG or "". */
std::string writePlot(const std::string& dir, const std::vector<RevisitTrial>& trials,
                      const std::vector<std::string>& methods)
{
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::string base = dir + "/revisits_success";
  std::ofstream dat(base + ".dat");
  for (const std::string& method : methods) {
    dat << "# " << method << ": bin, label, success @2 m (%), success @0.6 m (%), n\n";
    for (std::size_t b = 0; b < kDisjointBins; ++b) {
      const BinSummary s = summarizeBin(trials, method, bins()[b]);
      // gnuplot skips NaN (empty bins)
      dat << b << " \"" << bins()[b].label << "\" "
          << (s.n ? formatValue("%g", 100.0 * s.ok / s.n) : "NaN") << " "
          << (s.n ? formatValue("%g", 100.0 * s.ok_b / s.n) : "NaN") << " " << s.n
          << "\n";
    }
    dat << "\n\n";
  }
  dat.close();
  std::ostringstream gp;
  gp << "set title 'pcl_phaser_bench revisits: revisit pairs (RRE < 5 deg; solid: RTE "
        "< 2 m, dashed: RTE < 0.6 m)'\nset key outside right\nset grid\n"
     << "set xlabel 'distance between the scans'\nset xrange [-0.3:"
     << kDisjointBins - 0.7 << "]\nset ylabel 'success (%)'\nset yrange [0:105]\nplot ";
  for (std::size_t i = 0; i < methods.size(); ++i)
    gp << (i ? ", \\\n     " : "") << "'" << base << ".dat' index " << i
       << " using 1:3:xtic(2) with linespoints lc " << i + 1 << " dt 1 pt 7 title '"
       << methods[i] << " @2 m', '" << base << ".dat' index " << i
       << " using 1:4 with linespoints lc " << i + 1 << " dt 2 pt 6 title '"
       << methods[i] << " @0.6 m'";
  gp << "\n";
  return plotPng(base, "900,500", gp.str());
}

void writeReport(std::ostream& md, const std::vector<RevisitTrial>& trials,
                 const RevisitOptions& o, const std::string& origin, double fft_ms,
                 const std::vector<ScanPose>& poses)
{
  md << "Revisit pairs: " << origin << " (voxel of PCL's methods " << o.voxel << " m, "
     << o.engine.num_threads << " threads). Success @2 m: RRE < " << kRreThreshold
     << " deg and RTE < " << kRteThresholdA << " m; @0.6 m: RTE < " << kRteThresholdB
     << " m. Median RRE / RTE over the successes @2 m; time over all trials. False "
        "accepts: failures @2 m that the method reported as converged.\n\n"
     << yardstickLine(fft_ms);
  writeTable(md, trials, o.methods, fft_ms);
  md << "\nWhere the time goes: medians over all pairs.\n\n";
  writeStageTable(md, select(trials, [](const RevisitTrial&) { return true; }),
                  o.methods, fft_ms);
  md << "\nCovariance (getCovariance()) of the converged trials: NEES of the 6-D error "
        "(omega = Log(R_true R_est^T), nu = t_true - t_est) and of each block against "
        "the reference poses, which are LiDAR-inertial odometry (about a centimeter "
        "and a fraction of a degree of their own error).\n";
  writeNeesTable(md, trials, o.methods);
  const std::string drift = driftLine(trials, o.methods.front(), poses);
  if (!drift.empty())
    md << "\n" << drift;
}

/** The trials' CSV with its header, or null without \a path. */
std::unique_ptr<std::ofstream> openCsv(const std::string& path)
{
  if (path.empty())
    return nullptr;
  auto csv = std::make_unique<std::ofstream>(path);
  *csv << "method,source,target,dist,rel_rot,overlap,rre,rte,converged,ms,"
          "fitness_score,nees,nees_rot,nees_trans,sigma_rot_deg,sigma_trans_m";
  writeResultHeader(*csv);
  *csv << "\n";
  return csv;
}

/** Runs the study: every pair by every method, the report, the CSV and the plot. */
int runRevisitsStudy(BenchArguments& args)
{
  RevisitOptions o;
  if (!parseRevisitOptions(args, o))
    return args.fail();
  console::setVerbosityLevel(console::L_ERROR);
  const std::string folder =
      std::filesystem::path(o.data + "/" + kFolder).lexically_normal().string();
  const std::string pairs_file =
      o.pairs_file.empty() ? folder + "/pairs.txt" : o.pairs_file;
  const std::string poses_file = folder + "/poses_T_world_lidar.txt";
  for (const std::string& path :
       {folder, pairs_file, o.derived_pairs > 0 ? poses_file : folder})
    if (!std::filesystem::exists(path)) {
      std::fprintf(stderr, "revisits: %s not found, skipping\n", path.c_str());
      return 0;
    }
  std::vector<RevisitPair> pairs;
  std::vector<ScanPose> poses;
  std::string origin;
  if (!loadPairs(o, pairs_file, poses_file, poses, pairs, origin))
    return 1;
  if (!o.drift.empty() &&
      !correctReferences(Eigen::Vector3d(o.drift[0], o.drift[1], o.drift[2]), poses,
                         pairs, origin))
    return 1;
  if (o.max_pairs > 0 && pairs.size() > static_cast<std::size_t>(o.max_pairs))
    pairs.resize(static_cast<std::size_t>(o.max_pairs));
  const double fft_ms = fftYardstickMs();
  std::fprintf(stderr, "revisits: %zu pairs x %zu methods; yardstick FFT128 %.2f ms\n",
               pairs.size(), o.methods.size(), fft_ms);
  const std::unique_ptr<std::ofstream> csv = openCsv(o.csv);
  const std::vector<RevisitTrial> trials = runTrials(o, folder, pairs, csv.get());
  std::ofstream md_file;
  writeReport(openMarkdown(o.markdown, md_file, args.command()), trials, o, origin,
              fft_ms, poses);
  if (!o.plots.empty()) {
    const std::string png = writePlot(o.plots, trials, o.methods);
    if (!png.empty())
      std::fprintf(stderr, "wrote %s\n", png.c_str());
  }
  return trials.empty() && !pairs.empty() ? 1 : 0;
}

} // namespace

const Subcommand kRevisits = {
    "revisits",
    "the global aligners on the real revisit pairs of lidar/balm_handheld, by "
    "the distance between the scans",
    nullptr,
    {sharedOption("--data"),
     sharedOption("--pairs-file"),
     {"--derived-pairs", "N",
      "instead of the pairs file, up to N pairs per bin [3, 5), [5, 10), [10, "
      "15), [15, 21] m derived from the poses of poses_T_world_lidar.txt (scan "
      "gap >= 18, not in the pairs file either way), shuffled with --seed "
      "(default 0: off)"},
     sharedOption("--max-pairs"),
     {"--source-wedge", "F",
      "keep of each source only an azimuth sector of F x 360 deg about a random "
      "direction (seeded by --seed and the pair), in (0, 1] (default 1)"},
     sharedOption("--methods", "as compare's (default "
                               "phaser,phaser_xyz,sacia,prerejective)"),
     sharedOption("--seed", "seed of PCL's RANSAC (default 1)"),
     sharedOption("--voxel", "leaf (m) of PCL's methods (default 1)"),
     sharedOption("--fpcs-time"),
     sharedOption("--csv"),
     sharedOption("--md"),
     sharedOption("--plots", "revisits_success.{dat,gp,png} (PNG with gnuplot)"),
     sharedOption("--reference-drift",
                  "remove a linear drift of the odometry (world frame, m per "
                  "scan index: scan i's position - i x drift) from the reference "
                  "poses (the report fits one)")},
    true,
    2,
    runRevisitsStudy};

} // namespace bench
} // namespace pcl::phaser
