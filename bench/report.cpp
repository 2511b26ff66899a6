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
#include <iostream>
#include <map>
#include <sstream>

namespace pcl::phaser {
namespace bench {

void readStudyOptions(BenchArguments& args, StudyOptions& o,
                      std::vector<std::string> methods, double voxel)
{
  o.data = args.data();
  o.methods = args.list("--methods", std::move(methods));
  o.seed = static_cast<unsigned>(args.integer("--seed", 1));
  o.fpcs_seconds = static_cast<int>(args.integer("--fpcs-time", 10));
  o.voxel = args.number("--voxel", voxel);
  o.csv = args.text("--csv");
  o.markdown = args.text("--md");
  o.plots = args.text("--plots");
  o.engine = args.engine(2);
}

void checkStudyOptions(BenchArguments& args, const StudyOptions& o,
                       bool require_methods)
{
  args.check(!require_methods || !o.methods.empty(), "--methods: none given");
  for (const std::string& m : o.methods)
    args.check(findMethod(m) != nullptr, "--methods: unknown method " + m);
  args.check(o.engine.num_threads >= 1, "--threads: every method's, >= 1");
  args.check(o.fpcs_seconds >= 1, "--fpcs-time: >= 1");
}

Summary summarize(const std::vector<const Judged*>& group)
{
  Summary s;
  std::vector<double> rre, rte, ms;
  for (const Judged* t : group) {
    ++s.n;
    ms.push_back(t->ms);
    if (t->success) {
      ++s.ok;
      s.converged_ok += t->converged;
      rre.push_back(t->rre);
      rte.push_back(t->rte);
    } else {
      s.converged_failed += t->converged;
    }
  }
  s.median_rre = median(rre);
  s.median_rte = median(rte);
  s.median_ms = median(ms);
  s.p90_ms = quantile(ms, 0.9);
  return s;
}

NeesSummary summarizeNees(const std::vector<const Judged*>& group)
{
  constexpr double kChi2Six95 = 12.5916, kChi2Three95 = 7.8147; // 95 %: 6, 3 dof
  NeesSummary s;
  std::vector<double> nees, sigma_rot, sigma_trans;
  double sum = 0.0, rot = 0.0, trans = 0.0, rre2 = 0.0, rte2 = 0.0;
  for (const Judged* t : group) {
    if (!t->converged || t->nees.nees < 0.0)
      continue;
    ++s.n;
    nees.push_back(t->nees.nees);
    sum += t->nees.nees;
    s.inside += t->nees.nees <= kChi2Six95;
    s.inside_rot += t->nees.nees_rot >= 0.0 && t->nees.nees_rot <= kChi2Three95;
    s.inside_trans += t->nees.nees_trans >= 0.0 && t->nees.nees_trans <= kChi2Three95;
    rot += t->nees.nees_rot;
    trans += t->nees.nees_trans;
    rre2 += t->rre * t->rre;
    rte2 += t->rte * t->rte;
    sigma_rot.push_back(t->nees.sigma_rot_deg);
    sigma_trans.push_back(t->nees.sigma_trans_m);
  }
  if (s.n == 0)
    return s;
  s.mean = sum / s.n;
  s.median = median(nees);
  s.mean_rot = rot / s.n;
  s.mean_trans = trans / s.n;
  s.rms_rre = std::sqrt(rre2 / s.n);
  s.rms_rte = std::sqrt(rte2 / s.n);
  s.sigma_rot = median(sigma_rot);
  s.sigma_trans = median(sigma_trans);
  return s;
}

namespace {

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
        t.rre, t.rte, t.ms, t.converged, t.success, t.phaser ? std::nan("") : t.score,
        t.nees.nees, t.nees.nees_rot, t.nees.nees_trans, t.nees.sigma_rot_deg,
        t.nees.sigma_trans_m);
    out << line;
    writeResultCells(out, t.phaser ? &*t.phaser : nullptr);
    out << "\n";
  }
}

void writeStageTable(std::ostream& out, const std::vector<const Judged*>& group,
                     const std::vector<std::string>& methods, double fft_ms)
{
  double reference_ms = NAN; // the first method's median total
  out << tableHeader({"method", "stage", "median (ms)", "median (FFT128)",
                      "x " + methods.front() + "'s total"});
  for (const std::string& method : methods) {
    std::vector<const Judged*> mine;
    for (const Judged* t : group)
      if (t->method == method)
        mine.push_back(t);
    if (mine.empty())
      continue;
    const auto medianOf = [&](const std::string& stage) {
      std::vector<double> ms;
      for (const Judged* t : mine) {
        if (stage == "total")
          ms.push_back(t->ms);
        for (const auto& [name, stage_ms] : t->stages)
          if (name == stage)
            ms.push_back(stage_ms);
      }
      return median(ms);
    };
    StageList rows = {{"total", medianOf("total")}};
    for (const auto& stage : mine.front()->stages)
      rows.emplace_back(stage.first, medianOf(stage.first));
    if (method == methods.front())
      reference_ms = rows.front().second;
    for (const auto& [stage, value] : rows)
      out << "| " << method << " | " << stage << " | " << formatValue("%.1f", value)
          << " | " << formatValue("%.2f", value / fft_ms) << " | "
          << formatValue("%.3f", value / reference_ms) << " |\n";
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
           std::map<std::string, std::vector<const Judged*>>, decltype(&bySweepValue)>
      groups(&bySweepValue);
  for (const Trial& t : trials) {
    const auto key =
        by_set ? std::make_pair(t.set, 0.0) : std::make_pair(t.sweep, t.value);
    groups[key][t.method].push_back(&t);
  }
  out << tableHeader({by_set ? "pair / scan" : "condition", "method", "trials",
                      "success", "median RRE (deg)", "median RTE (m)",
                      "median time (ms)", "p90 time (ms)"});
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
  std::map<int, std::vector<const Judged*>> by_bandwidth;
  for (const Trial& t : trials)
    by_bandwidth[t.bandwidth].push_back(&t);
  out << "| bandwidth | trials | converged | mean NEES (6 = consistent) | median NEES "
         "| "
         "inside 95 % ellipsoid | mean NEES rot. / trans. (3 = consistent) | RMS RRE "
         "(deg) | RMS RTE (m) | median sigma_rot (deg) | "
         "median sigma_trans (m) |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [bandwidth, group] : by_bandwidth) {
    const NeesSummary s = summarizeNees(group);
    out << "| " << bandwidth << " | " << group.size() << " | " << s.n << " | "
        << formatValue("%.2f", s.mean) << " | " << formatValue("%.2f", s.median)
        << " | " << formatValue("%.0f %%", 100.0 * s.inside / s.n) << " | "
        << formatValue("%.2f", s.mean_rot) << " / " << formatValue("%.2f", s.mean_trans)
        << " | " << formatValue("%.3f", s.rms_rre) << " | "
        << formatValue("%.3f", s.rms_rte) << " | " << formatValue("%.3f", s.sigma_rot)
        << " | " << formatValue("%.3f", s.sigma_trans) << " |\n";
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
  for (const std::string sweep : {"noise", "sparsity", "overlap"}) {
    std::map<std::string, std::map<double, std::vector<const Judged*>>> series;
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
    std::ostringstream gp;
    const char* xlabel = sweep == "noise"      ? "PSNR (dB)"
                         : sweep == "sparsity" ? "points kept (%)"
                                               : "overlap (% of the azimuth circle)";
    gp << "set multiplot layout 1,2 title 'pcl_phaser_bench compare: " << sweep
       << " sweep'\nset key bottom left\nset grid\nset xlabel '" << xlabel
       << "'\nset xrange [*:*] reverse\n"
       << "set ylabel 'success (%)'\nset yrange [0:105]\n"
       << "plot for [i=0:" << series.size() - 1 << "] '" << base
       << ".dat' index i using 1:2 with linespoints title columnheader(1)\n"
       << "set ylabel 'median RRE of successes (deg)'\nset yrange [0:*]\n"
       << "plot for [i=0:" << series.size() - 1 << "] '" << base
       << ".dat' index i using 1:3 with linespoints title columnheader(1)\n"
       << "unset multiplot\n";
    if (const std::string png = plotPng(base, "1000,420", gp.str()); !png.empty())
      pngs.push_back(png);
  }
  return pngs;
}

std::string plotPng(const std::string& base, const char* size,
                    const std::string& script)
{
  std::ofstream(base + ".gp") << "set terminal pngcairo size " << size
                              << " font ',11' noenhanced\nset output '" << base
                              << ".png'\n"
                              << script;
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0)
    return "";
  return std::system(("gnuplot '" + base + ".gp'").c_str()) == 0 ? base + ".png" : "";
}

std::ostream& openMarkdown(const std::string& path, std::ofstream& file,
                           const std::string& command)
{
  if (!path.empty())
    file.open(path);
  std::ostream& md = path.empty() ? std::cout : file;
  md << "Command: `" << command << "`\n\n";
  return md;
}

std::string yardstickLine(double fft_ms)
{
  return "Yardstick: one 128^3 real-to-complex FFT (FFTW_MEASURE, 1 thread) = " +
         formatValue("%.2f", fft_ms) + " ms (FFT128).\n\n";
}

std::string tableHeader(const std::vector<std::string>& columns)
{
  std::string names = "|", rule = "|";
  for (const std::string& column : columns) {
    names += " " + column + " |";
    rule += "---|";
  }
  return names + "\n" + rule + "\n";
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
