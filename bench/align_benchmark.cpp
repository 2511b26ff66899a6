/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_align_benchmark: time per PhaserRegistration::align on a LiDAR pair at the
 * defaults, with 1 and 2 threads, with a fresh and with a cached target, broken down by
 * stage. Without files it uses the simulated demo pair (64 beams, ~113k points each).
 *
 *   pcl_phaser_align_benchmark [SOURCE TARGET] [-r repetitions] [-b bandwidth]
 *                              [-range_only] [-plain] [-busy]
 *                              [-orientation_candidates N] [-max_tilt DEG]
 *                              [-first threads [-warm_up [-keep_memory]]]
 * -range_only switches the intensity channel off, so the two runs show what fusing one
 * extra channel costs per stage; -plain refines the rotation on plain C only, not also
 * on the energy-normalized correlation (PhaserParameters::normalized_refinement =
 * false); -busy keeps one core busy with a spinning child process during the aligns (as
 * `yes > /dev/null` would: a robot running other nodes); -orientation_candidates sets
 * PhaserParameters::orientation_candidates (default 10). Timings are wall-clock; every
 * stage is printed in ms and in FFT units (one 128^3 r2c FFT on one thread, measured
 * first), and the first align of each configuration (plans and tables built) is printed
 * apart. -first runs the first align of the process instead, before anything else has
 * run (the yardstick is measured after it: its buffers would warm the allocator), then
 * the next fresh and the cached aligns, with the minor page faults of each and the
 * first transformation in full (doc/benchmarks.md, "First align in a process");
 * -warm_up runs pcl::phaser::warmUp on a thread while the clouds are read (as a batch
 * tool would) and prints its time and the reading's, -keep_memory sets its
 * WarmUpOptions::keep_memory. -max_tilt DEG (or --max-tilt) compares, with 2 threads
 * and a cached target, the full search with the gravity prior
 * PhaserParameters::max_tilt_deg = DEG, their aligns alternating, and prints the ratio.
 */
#include "bench_timing.h"
#include "cloud_reading.h"
#include "fft_yardstick.h"
#include "scan_simulator.h"

#include <pcl_phaser/core/warm_up.h>
#include <pcl_phaser/phaser_registration.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/filters/filter.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <optional>
#include <string>
#include <sys/types.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace {

using PointT = pcl::PointXYZI;
using Cloud = pcl::PointCloud<PointT>;
using namespace pcl::phaser::bench;

struct Row {
  double total = 0.0;
  double first = 0.0; ///< the first align of the configuration (the warm-up)
  pcl::phaser::PhaserResult estimate;
};

/** A child process that spins on one core until stop() (or the parent's exit). */
class BusyCore {
public:
  BusyCore()
  {
    pid_ = fork();
    if (pid_ == 0)
      for (volatile unsigned long i = 0;; i = i + 1) {
      }
  }
  ~BusyCore() { stop(); }
  BusyCore(const BusyCore&) = delete;
  BusyCore& operator=(const BusyCore&) = delete;
  bool running() const { return pid_ > 0; }
  void stop()
  {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
      pid_ = -1;
    }
  }

private:
  pid_t pid_ = -1;
};

/** \a phaser on \a source and \a target with \a params and \a threads threads,
 *  intensity fused unless \a range_only. */
void configure(pcl::PhaserRegistration<PointT, PointT>& phaser,
               const Cloud::Ptr& source, const Cloud::Ptr& target, int threads,
               const pcl::phaser::PhaserParameters& params, bool range_only)
{
  phaser.setUseIntensity(!range_only);
  phaser.setParameters(params);
  phaser.setNumberOfThreads(threads);
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
}

/** Median (by total time) of \a reps aligns with \a params and \a threads threads;
 *  \a cached keeps the target model between. */
Row measure(const Cloud::Ptr& source, const Cloud::Ptr& target, int threads,
            bool cached, int reps, const pcl::phaser::PhaserParameters& params,
            bool range_only)
{
  std::vector<Row> rows;
  pcl::PhaserRegistration<PointT, PointT> phaser;
  configure(phaser, source, target, threads, params, range_only);
  Cloud out;
  // Warm-up: plans and tables (the first align of this configuration), and the target
  // cache when cached.
  const auto warm = Clock::now();
  phaser.align(out);
  const double first = msSince(warm);
  for (int i = 0; i < reps; ++i) {
    if (!cached)
      phaser.setInputTarget(target);
    const auto start = Clock::now();
    phaser.align(out);
    Row r;
    r.total = msSince(start);
    r.first = first;
    r.estimate = phaser.getResult();
    rows.push_back(r);
  }
  std::sort(rows.begin(), rows.end(),
            [](const Row& a, const Row& b) { return a.total < b.total; });
  return rows[rows.size() / 2];
}

/** Median by time. */
Timing median(std::vector<Timing> runs)
{
  std::sort(runs.begin(), runs.end(),
            [](const Timing& a, const Timing& b) { return a.ms < b.ms; });
  return runs[runs.size() / 2];
}

/** The first align of the process, then the medians of \a reps fresh (the target set
 *  again) and \a reps cached aligns, each printed with its page faults, in ms and in
 *  FFT units of a yardstick measured after them; the first transformation in full. */
void firstInProcess(const Cloud::Ptr& source, const Cloud::Ptr& target, int threads,
                    int reps, const pcl::phaser::PhaserParameters& params,
                    bool range_only)
{
  pcl::PhaserRegistration<PointT, PointT> phaser;
  configure(phaser, source, target, threads, params, range_only);
  const Timing first = timedAlign(phaser);
  const Eigen::Matrix4d transformation = phaser.getResult().transformation;
  std::vector<Timing> fresh, cached;
  for (int i = 0; i < reps; ++i) {
    phaser.setInputTarget(target);
    fresh.push_back(timedAlign(phaser));
  }
  for (int i = 0; i < reps; ++i)
    cached.push_back(timedAlign(phaser));
  const Timing f = median(fresh), c = median(cached);
  const double unit = pcl::phaser::bench::fftYardstickMs();
  std::printf(
      "yardstick (measured after the aligns): one 128^3 r2c FFT (1 thread) = "
      "%.2f ms\n\n| threads | first | next fresh | cached | first / next "
      "fresh | page faults first / fresh / cached |\n|---|---|---|---|---|---|\n"
      "| %d | %.1f ms / %.1f | %.1f ms / %.1f | %.1f ms / %.1f | %.2fx | %ld / "
      "%ld / %ld |\n\nfirst transformation:",
      unit, threads, first.ms, first.ms / unit, f.ms, f.ms / unit, c.ms, c.ms / unit,
      first.ms / f.ms, first.faults, f.faults, c.faults);
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 4; ++k)
      std::printf(" %.17g", transformation(r, k));
  std::printf("\n");
}

bool loadPair(int argc, char** argv, Cloud::Ptr& source, Cloud::Ptr& target,
              std::string& name)
{
  const std::vector<int> files = pcl::console::parse_file_extension_argument(
      argc, argv, std::vector<std::string>{".pcd", ".ply", ".bin"});
  source = pcl::make_shared<Cloud>();
  target = pcl::make_shared<Cloud>();
  if (files.size() >= 2) {
    std::string error;
    if (!pcl::phaser::loadCloud(argv[files[0]], *source, &error) ||
        !pcl::phaser::loadCloud(argv[files[1]], *target, &error)) {
      pcl::console::print_error("%s\n", error.c_str());
      return false;
    }
    pcl::Indices kept;
    pcl::removeNaNFromPointCloud(*source, *source, kept);
    pcl::removeNaNFromPointCloud(*target, *target, kept);
    name = std::string(argv[files[0]]) + " -> " + argv[files[1]];
    return true;
  }
  const pcl::phaser::ScanPair pair = pcl::phaser::makeDemoPair(1);
  *source = pair.source;
  *target = pair.target;
  name = "simulated demo pair (seed 1)";
  return true;
}

/** -first: reads the pair, with -warm_up while pcl::phaser::warmUp runs on a thread,
 *  then firstInProcess. */
int firstAlignRun(int argc, char** argv, const pcl::phaser::PhaserParameters& params,
                  int reps, bool range_only)
{
  pcl::phaser::WarmUpOptions options;
  options.channels = range_only ? 0 : 1;
  options.keep_memory = pcl::console::find_switch(argc, argv, "-keep_memory");
  const bool warm = pcl::console::find_switch(argc, argv, "-warm_up");
  double warm_ms = 0.0;
  std::string warm_error;
  const auto start = Clock::now();
  std::thread warm_up;
  if (warm)
    warm_up = std::thread([&] {
      warm_error = pcl::phaser::warmUp(params, options);
      warm_ms = msSince(start);
    });
  Cloud::Ptr source, target;
  std::string name;
  const bool loaded = loadPair(argc, argv, source, target, name);
  const double load_ms = msSince(start);
  if (warm)
    warm_up.join();
  if (!loaded || !warm_error.empty()) {
    pcl::console::print_error("%s\n", warm_error.c_str());
    return 2;
  }
  std::printf("pair: %s (%zu -> %zu points), bandwidth %d, first align of the process, "
              "then medians of %d\nreading the pair: %.1f ms; warm-up%s: %s\n",
              name.c_str(), source->size(), target->size(), params.bandwidth, reps,
              load_ms, options.keep_memory ? " (memory kept)" : "",
              warm ? (std::to_string(warm_ms) +
                      " ms, on a thread beside the reading, "
                      "waited for " +
                      std::to_string(std::max(0.0, warm_ms - load_ms)) + " ms")
                         .c_str()
                   : "none");
  firstInProcess(source, target, params.num_threads, reps, params, range_only);
  return 0;
}

/** One result's row of the -max_tilt table: median total and stages (ms / FFT units),
 *  tilt of the estimate (deg), converged. */
void printTiltRow(const char* label, const Row& r, double unit)
{
  const pcl::phaser::StageTimes& t = r.estimate.diagnostics.times;
  const Eigen::Matrix4d& T = r.estimate.transformation;
  const double tilt = std::acos(std::clamp(T(2, 2), -1.0, 1.0)) * 180.0 / M_PI;
  std::printf(
      "| %s | %.1f / %.2f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %zu "
      "| %.2f | %s |\n",
      label, r.total, r.total / unit, t.sht, t.so3, t.refinement, t.translation,
      t.orientation, t.verification, r.total - t.total(),
      r.estimate.diagnostics.hypotheses.size(), tilt,
      r.estimate.converged ? "yes" : "no");
}

/** -max_tilt: the full search and the prior, 2 threads, cached targets, \a reps aligns
 *  of each alternating (both see the same load); medians and their ratio. */
void compareTilt(const Cloud::Ptr& source, const Cloud::Ptr& target, int reps,
                 pcl::phaser::PhaserParameters params, bool range_only, double unit)
{
  const double max_tilt = params.max_tilt_deg;
  pcl::PhaserRegistration<PointT, PointT> full, prior;
  params.max_tilt_deg = 0.0;
  configure(full, source, target, 2, params, range_only);
  params.max_tilt_deg = max_tilt;
  configure(prior, source, target, 2, params, range_only);
  Cloud out;
  full.align(out); // warm-up: plans, tables, the target caches
  prior.align(out);
  std::vector<Row> rows[2];
  for (int i = 0; i < reps; ++i)
    for (int k = 0; k < 2; ++k) {
      auto& phaser = k == 0 ? full : prior;
      const auto start = Clock::now();
      phaser.align(out);
      Row r;
      r.total = msSince(start);
      r.estimate = phaser.getResult();
      rows[k].push_back(r);
    }
  for (auto& v : rows)
    std::sort(v.begin(), v.end(),
              [](const Row& a, const Row& b) { return a.total < b.total; });
  const Row& f = rows[0][rows[0].size() / 2];
  const Row& p = rows[1][rows[1].size() / 2];
  std::printf("| search (2 threads, cached) | total | SHT | SO(3) corr | refinement | "
              "translation | orientation | verification | other | hypotheses | "
              "tilt (deg) | converged |\n|---|---|---|---|---|---|---|---|---|---|---|"
              "---|\n");
  printTiltRow("full", f, unit);
  char label[64];
  std::snprintf(label, sizeof(label), "max_tilt %g deg", max_tilt);
  printTiltRow(label, p, unit);
  std::printf("\nratio max_tilt / full: %.2f\n", p.total / f.total);
}

/** Every stage of the median fresh and cached align with 1 and 2 threads, in ms and
 *  FFT units of \a unit ms. */
void printStageTable(const Cloud::Ptr& source, const Cloud::Ptr& target, int reps,
                     const pcl::phaser::PhaserParameters& params, bool range_only,
                     double unit)
{
  std::printf("| threads | target | total | first | target prep | sampling | SHT "
              "| SO(3) corr | refinement | translation | orientation | verification "
              "| other | passes |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const auto cell = [unit](double ms) {
    char text[48];
    std::snprintf(text, sizeof(text), "%.1f / %.2f", ms, ms / unit);
    return std::string(text);
  };
  for (int threads : {1, 2})
    for (bool cached : {false, true}) {
      const Row r = measure(source, target, threads, cached, reps, params, range_only);
      const pcl::phaser::PhaserResult& e = r.estimate;
      const pcl::phaser::StageTimes& times = e.diagnostics.times;
      std::printf("| %d | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s "
                  "| %d |\n",
                  threads, cached ? "cached" : "fresh", cell(r.total).c_str(),
                  cell(r.first).c_str(), cell(times.target).c_str(),
                  cell(times.sampling).c_str(), cell(times.sht).c_str(),
                  cell(times.so3).c_str(), cell(times.refinement).c_str(),
                  cell(times.translation).c_str(), cell(times.orientation).c_str(),
                  cell(times.verification).c_str(),
                  cell(r.total - times.total()).c_str(), e.diagnostics.passes);
      std::fflush(stdout);
    }
}

} // namespace

int main(int argc, char** argv)
{
  int reps = 7;
  pcl::phaser::PhaserParameters params; // bandwidth 64 unless -b
  pcl::console::parse_argument(argc, argv, "-r", reps);
  pcl::console::parse_argument(argc, argv, "-b", params.bandwidth);
  pcl::console::parse_argument(argc, argv, "-orientation_candidates",
                               params.orientation_candidates);
  const bool range_only = pcl::console::find_switch(argc, argv, "-range_only");
  const bool normalized = !pcl::console::find_switch(argc, argv, "-plain");
  const bool busy = pcl::console::find_switch(argc, argv, "-busy");
  if (pcl::console::parse_argument(argc, argv, "-max_tilt", params.max_tilt_deg) < 0)
    pcl::console::parse_argument(argc, argv, "--max-tilt", params.max_tilt_deg);
  params.normalized_refinement = normalized;
  const std::string problem = pcl::phaser::validateParameters(params);
  if (reps < 1 || !problem.empty()) {
    pcl::console::print_error("%s\n",
                              reps < 1 ? "repetitions must be >= 1" : problem.c_str());
    return 1;
  }
  int first_threads = 0;
  if (pcl::console::parse_argument(argc, argv, "-first", first_threads) >= 0) {
    params.num_threads = first_threads;
    return firstAlignRun(argc, argv, params, reps, range_only);
  }
  Cloud::Ptr source, target;
  std::string name;
  if (!loadPair(argc, argv, source, target, name))
    return 2;
  const double unit = pcl::phaser::bench::fftYardstickMs();
  std::optional<BusyCore> spinner;
  if (busy)
    spinner.emplace();
  std::printf(
      "pair: %s (%zu -> %zu points), bandwidth %d, channels: %s, %s refinement, "
      "median of %d%s; yardstick: one 128^3 r2c FFT (1 thread) = %.2f ms\n"
      "Each cell: ms / FFT units. \"first\": the first align of the configuration "
      "(tables and plans built the first time).\n\n",
      name.c_str(), source->size(), target->size(), params.bandwidth,
      range_only ? "range" : "range + intensity", normalized ? "normalized" : "plain",
      reps, busy ? ", one core kept busy by a spinning process" : "", unit);
  if (params.max_tilt_deg > 0.0) {
    compareTilt(source, target, reps, params, range_only, unit);
    return 0;
  }
  printStageTable(source, target, reps, params, range_only, unit);
  return 0;
}
