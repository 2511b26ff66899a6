/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_bench align: the time of PhaserRegistration::align on a pair (or the
 * simulated demo pair), by stage, with 1 and 2 threads, fresh and cached target, in ms
 * and FFT units; --first: the first align of a process; --max-tilt: the gravity prior
 * against the full search (the options: alignSubcommand()).
 */
#include "bench_timing.h"
#include "cloud_reading.h"
#include "fft_yardstick.h"
#include "methods.h"
#include "scan_simulator.h"
#include "subcommands.h"

#include <pcl_phaser/core/warm_up.h>
#include <pcl_phaser/phaser_registration.h>

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

/** The pair of \a files (SOURCE TARGET), or the simulated demo pair without files. */
bool loadPair(const std::vector<std::string>& files, Cloud::Ptr& source,
              Cloud::Ptr& target, std::string& name)
{
  if (files.size() == 2) {
    source = loadFiniteScan(files[0]);
    target = loadFiniteScan(files[1]);
    name = files[0] + " -> " + files[1];
    return source && target; // the loader said why not
  }
  const pcl::phaser::ScanPair pair = pcl::phaser::makeDemoPair(1);
  source = pcl::make_shared<Cloud>(pair.source);
  target = pcl::make_shared<Cloud>(pair.target);
  name = "simulated demo pair (seed 1)";
  return true;
}

/** --first: reads the pair, with --warm-up while pcl::phaser::warmUp runs on a thread,
 *  then firstInProcess. */
int firstAlignRun(const BenchArguments& args,
                  const pcl::phaser::PhaserParameters& params, int reps,
                  bool range_only)
{
  pcl::phaser::WarmUpOptions options;
  options.channels = range_only ? 0 : 1;
  options.keep_memory = args.has("--keep-memory");
  const bool warm = args.has("--warm-up");
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
  const bool loaded = loadPair(args.files(), source, target, name);
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

/** One result's row of the --max-tilt table: median total and stages (ms / FFT units),
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

/** --max-tilt: the full search and the prior, 2 threads, cached targets, \a reps aligns
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

/** Reads the options, the pair and the yardstick, then the stage table or the
 *  --max-tilt comparison (or the --first run). */
int runAlign(BenchArguments& args)
{
  const int reps = static_cast<int>(args.integer("--reps", 7));
  pcl::phaser::PhaserParameters params = args.engine(0); // bandwidth 64 unless given
  const bool range_only = args.has("--range-only"), busy = args.has("--busy");
  const bool normalized = params.normalized_refinement;
  args.check(reps >= 1, "--reps: >= 1");
  args.check(args.files().empty() || args.files().size() == 2,
             "expected SOURCE TARGET or no files");
  if (!args.ok())
    return args.fail();
  if (args.has("--first"))
    return firstAlignRun(args, params, reps, range_only);
  Cloud::Ptr source, target;
  std::string name;
  if (!loadPair(args.files(), source, target, name))
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

} // namespace

const pcl::phaser::bench::Subcommand pcl::phaser::bench::kAlign = {
    "align",
    "the time of one align by stage: 1 and 2 threads, fresh and cached target "
    "(SOURCE TARGET, or the simulated demo pair); with --max-tilt DEG the gravity "
    "prior against the full search (2 threads, cached, alternating)",
    "[SOURCE TARGET]",
    {{"--reps", "N", "aligns per configuration, the median printed (default 7)"},
     {"--range-only", nullptr, "the intensity channel off: what fusing it costs"},
     {"--busy", nullptr,
      "one core kept busy by a spinning process (as `yes > /dev/null` would)"},
     {"--first", nullptr,
      "the first align of the process (with --threads' threads), then the next "
      "fresh and cached ones, with their page faults"},
     {"--warm-up", nullptr,
      "with --first: pcl::phaser::warmUp on a thread while the pair is read"},
     {"--keep-memory", nullptr, "with --warm-up: WarmUpOptions::keep_memory"}},
    true,
    0,
    runAlign};
