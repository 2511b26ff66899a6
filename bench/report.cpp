/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "protocol.h"
#include "report.h"
#include "result_csv.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

namespace pcl::phaser {
namespace bench {

namespace {

struct Summary {
  int n = 0, ok = 0;
  double median_rre = NAN, median_rte = NAN, median_ms = NAN, p90_ms = NAN;
};

Summary summarize(const std::vector<const Trial*>& group)
{
  Summary s;
  std::vector<double> rre, rte, ms;
  for (const Trial* t : group) {
    ++s.n;
    ms.push_back(t->ms);
    if (t->success) {
      ++s.ok;
      rre.push_back(t->rre_deg);
      rte.push_back(t->rte_m);
    }
  }
  s.median_rre = median(rre);
  s.median_rte = median(rte);
  s.median_ms = median(ms);
  s.p90_ms = quantile(ms, 0.9);
  return s;
}

bool bySweepValue(const std::pair<std::string, double>& a,
                  const std::pair<std::string, double>& b)
{
  if (a.first != b.first)
    return a.first < b.first;
  // noise: high PSNR (clean) first; fractions: large (easy) first
  return a.second > b.second;
}

} // namespace

void writeCsv(std::ostream& out, const std::vector<Trial>& trials)
{
  out << "set,sweep,value,pose,method,bandwidth,rre_deg,rte_m,time_ms,converged,"
         "success,fitness_score,nees,nees_rot,nees_trans,sigma_rot_deg,sigma_trans_m";
  writeResultHeader(out);
  out << "\n";
  char line[512];
  for (const Trial& t : trials) {
    std::snprintf(
        line, sizeof(line),
        "%s,%s,%g,%d,%s,%d,%.6f,%.6f,%.3f,%d,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g",
        t.set.c_str(), t.sweep.c_str(), t.value, t.pose, t.method.c_str(), t.bandwidth,
        t.rre_deg, t.rte_m, t.ms, t.converged, t.success,
        t.phaser ? std::nan("") : t.score, t.nees, t.nees_rot, t.nees_trans,
        t.sigma_rot_deg, t.sigma_trans_m);
    out << line;
    writeResultCells(out, t.phaser ? &*t.phaser : nullptr);
    out << "\n";
  }
}

void writeSummary(std::ostream& out, const std::vector<Trial>& trials, bool by_set)
{
  // Keys keep first-seen order of methods inside each group.
  std::vector<std::string> methods;
  for (const Trial& t : trials)
    if (std::find(methods.begin(), methods.end(), t.method) == methods.end())
      methods.push_back(t.method);
  std::map<std::pair<std::string, double>,
           std::map<std::string, std::vector<const Trial*>>, decltype(&bySweepValue)>
      groups(&bySweepValue);
  for (const Trial& t : trials) {
    const auto key =
        by_set ? std::make_pair(t.set, 0.0) : std::make_pair(t.sweep, t.value);
    groups[key][t.method].push_back(&t);
  }
  out << (by_set ? "| pair / scan " : "| condition ")
      << "| method | trials | success | median RRE (deg) | median RTE (m) | median "
         "time "
         "(ms) | p90 time (ms) |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& [key, per_method] : groups) {
    std::string name = key.first;
    if (!by_set && key.first == "unrelated")
      name = "unrelated scenes";
    else if (!by_set && key.first != "clean") {
      Condition c;
      c.kind = key.first == "noise"      ? Condition::Kind::Noise
               : key.first == "sparsity" ? Condition::Kind::Sparsity
                                         : Condition::Kind::Overlap;
      c.value = key.second;
      name = c.label();
    }
    for (const std::string& m : methods) {
      const auto it = per_method.find(m);
      if (it == per_method.end())
        continue;
      const Summary s = summarize(it->second);
      out << "| " << name << " | " << m << " | " << s.n << " | "
          << formatValue("%.0f %%", 100.0 * s.ok / s.n) << " | "
          << formatValue("%.2f", s.median_rre) << " | "
          << formatValue("%.3f", s.median_rte) << " | "
          << formatValue("%.0f", s.median_ms) << " | " << formatValue("%.0f", s.p90_ms)
          << " |\n";
    }
  }
}

void writeNeesSummary(std::ostream& out, const std::vector<Trial>& trials)
{
  std::map<int, std::vector<const Trial*>> by_bandwidth;
  for (const Trial& t : trials)
    by_bandwidth[t.bandwidth].push_back(&t);
  out << "| bandwidth | trials | converged | mean NEES (6 = consistent) | median NEES "
         "| "
         "inside 95 % ellipsoid | mean NEES rot. / trans. (3 = consistent) | RMS RRE "
         "(deg) | RMS RTE (m) | median sigma_rot (deg) | "
         "median sigma_trans (m) |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [bandwidth, group] : by_bandwidth) {
    int converged = 0, inside = 0;
    double sum_nees = 0.0, sum_rre2 = 0.0, sum_rte2 = 0.0, sum_rot = 0.0,
           sum_trans = 0.0;
    std::vector<double> nees, sigma_rot, sigma_trans;
    for (const Trial* t : group) {
      if (!t->converged || t->nees < 0.0)
        continue;
      ++converged;
      sum_nees += t->nees;
      sum_rot += t->nees_rot;
      sum_trans += t->nees_trans;
      nees.push_back(t->nees);
      inside += t->nees <= 12.5916; // chi-square, 6 dof, 95 %
      sum_rre2 += t->rre_deg * t->rre_deg;
      sum_rte2 += t->rte_m * t->rte_m;
      sigma_rot.push_back(t->sigma_rot_deg);
      sigma_trans.push_back(t->sigma_trans_m);
    }
    const double n = converged;
    out << "| " << bandwidth << " | " << group.size() << " | " << converged << " | "
        << formatValue("%.2f", sum_nees / n) << " | "
        << formatValue("%.2f", median(nees)) << " | "
        << formatValue("%.0f %%", 100.0 * inside / n) << " | "
        << formatValue("%.2f", sum_rot / n) << " / "
        << formatValue("%.2f", sum_trans / n) << " | "
        << formatValue("%.3f", std::sqrt(sum_rre2 / n)) << " | "
        << formatValue("%.3f", std::sqrt(sum_rte2 / n)) << " | "
        << formatValue("%.3f", median(sigma_rot)) << " | "
        << formatValue("%.3f", median(sigma_trans)) << " |\n";
  }
}

void writeDetectionSummary(std::ostream& out, const std::vector<Trial>& trials,
                           const std::vector<double>& thresholds)
{
  std::map<std::string, std::vector<const Trial*>> by_method;
  for (const Trial& t : trials)
    by_method[t.method].push_back(&t);
  out << "| method | detector | correct | wrong | true pos. | false pos. | precision | "
         "recall |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& [method, group] : by_method) {
    auto row = [&, &method = method](const std::string& name, auto accepted) {
      int correct = 0, wrong = 0, tp = 0, fp = 0;
      for (const Trial* t : group) {
        (t->success ? correct : wrong)++;
        if (accepted(*t))
          (t->success ? tp : fp)++;
      }
      out << "| " << method << " | " << name << " | " << correct << " | " << wrong
          << " | " << tp << " | " << fp << " | "
          << formatValue("%.3f", tp + fp ? double(tp) / (tp + fp) : NAN) << " | "
          << formatValue("%.3f", correct ? double(tp) / correct : NAN) << " |\n";
    };
    row("hasConverged()", [](const Trial& t) { return t.converged; });
    for (double threshold : thresholds)
      row(formatValue("score >= %g", threshold),
          [threshold](const Trial& t) { return t.score >= threshold; });
  }
}

std::vector<std::string> writePlots(const std::string& dir,
                                    const std::vector<Trial>& trials)
{
  std::vector<std::string> pngs;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const bool have_gnuplot = std::system("command -v gnuplot > /dev/null 2>&1") == 0;
  for (const std::string sweep : {"noise", "sparsity", "overlap"}) {
    std::map<std::string, std::map<double, std::vector<const Trial*>>> series;
    bool any = false;
    for (const Trial& t : trials)
      if (t.sweep == sweep) {
        series[t.method][t.value].push_back(&t);
        any = true;
      }
    if (!any)
      continue;
    // The clean trials are the 100 % point of the sparsity and overlap sweeps.
    if (sweep != "noise")
      for (const Trial& t : trials)
        if (t.sweep == "clean" && series.count(t.method))
          series[t.method][1.0].push_back(&t);
    const std::string base = dir + "/sweep_" + sweep;
    std::ofstream dat(base + ".dat");
    for (const auto& [method, points] : series) {
      dat << "\"" << method << "\"\n";
      for (const auto& [value, group] : points) {
        const Summary s = summarize(group);
        const double x = sweep == "noise" ? value : 100.0 * value;
        // gnuplot skips NaN (its "missing" setting breaks columnheader titles)
        dat << x << " " << 100.0 * s.ok / s.n << " "
            << (std::isfinite(s.median_rre) ? formatValue("%g", s.median_rre) : "NaN")
            << "\n";
      }
      dat << "\n\n";
    }
    std::ofstream gp(base + ".gp");
    const char* xlabel = sweep == "noise"      ? "PSNR (dB)"
                         : sweep == "sparsity" ? "points kept (%)"
                                               : "overlap (% of the azimuth circle)";
    gp << "set terminal pngcairo size 1000,420 font ',11' noenhanced\nset output '"
       << base
       << ".png'\nset multiplot layout 1,2 title 'pcl_phaser_bench compare: " << sweep
       << " sweep'\nset key bottom left\nset grid\nset xlabel '" << xlabel
       << "'\nset xrange [*:*] reverse\n"
       << "set ylabel 'success (%)'\nset yrange [0:105]\n"
       << "plot for [i=0:" << series.size() - 1 << "] '" << base
       << ".dat' index i using 1:2 with linespoints title columnheader(1)\n"
       << "set ylabel 'median RRE of successes (deg)'\nset yrange [0:*]\n"
       << "plot for [i=0:" << series.size() - 1 << "] '" << base
       << ".dat' index i using 1:3 with linespoints title columnheader(1)\n"
       << "unset multiplot\n";
    gp.close();
    if (have_gnuplot && std::system(("gnuplot '" + base + ".gp'").c_str()) == 0)
      pngs.push_back(base + ".png");
  }
  return pngs;
}

std::string formatValue(const char* fmt, double value)
{
  if (!std::isfinite(value))
    return "-";
  char text[64];
  std::snprintf(text, sizeof(text), fmt, value);
  return text;
}

} // namespace bench
} // namespace pcl::phaser
