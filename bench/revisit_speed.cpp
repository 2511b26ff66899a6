/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_bench speed: the time of pcl::PhaserRegistration::align on revisit pairs
 * in a warm process: fresh and cached aligns with 1 and 2 engine threads by stage and
 * page faults, two aligns in two threads against the same two in series, and the fused
 * align against a range-only one; medians over the pairs in ms and FFT units.
 */
#include "bench_timing.h"
#include "cloud_reading.h"
#include "fft_yardstick.h"
#include "methods.h"
#include "protocol.h"
#include "revisits.h"
#include "subcommands.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/filters/filter.h>
#include <pcl/point_types.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

namespace {

using PointT = pcl::PointXYZI;
using Cloud = pcl::PointCloud<PointT>;
using namespace pcl::phaser::bench;

struct Pair {
  Cloud::Ptr source, target;
};

/** The first \a max_pairs (0: all) pairs of \a file (readPairs() of revisits.h), their
 *  scans read from its folder; false with a message when the file is absent or
 *  malformed, or a scan unreadable. */
bool loadPairs(const std::string& file, int max_pairs, std::vector<Pair>& pairs)
{
  if (!std::filesystem::exists(file)) {
    std::printf("skipped: %s not found (the shared data is absent)\n", file.c_str());
    return false;
  }
  std::vector<RevisitPair> listed;
  std::string error;
  if (!readPairs(file, listed, error))
    return std::fprintf(stderr, "speed: %s\n", error.c_str()), false;
  const std::string folder = file.substr(0, file.find_last_of('/') + 1);
  for (const RevisitPair& r : listed) {
    if (max_pairs > 0 && static_cast<int>(pairs.size()) >= max_pairs)
      break;
    const Pair p{loadFiniteScan(folder + r.source), loadFiniteScan(folder + r.target)};
    if (!p.source || !p.target)
      return false; // the loader said why
    pairs.push_back(p);
  }
  return !pairs.empty();
}

/** The fresh and cached aligns of every pair with \a threads engine threads. */
void timePairs(const std::vector<Pair>& pairs, int threads, std::vector<Timing>& fresh,
               std::vector<Timing>& cached)
{
  for (const Pair& p : pairs) {
    pcl::PhaserRegistration<PointT, PointT> phaser;
    phaser.setNumberOfThreads(threads);
    phaser.setInputSource(p.source);
    phaser.setInputTarget(p.target);
    fresh.push_back(timedAlign(phaser));
    cached.push_back(timedAlign(phaser));
  }
}

/** Median of \a field over \a runs, in ms. */
template <typename Field>
double medianOf(const std::vector<Timing>& runs, const Field& field)
{
  std::vector<double> v;
  for (const Timing& t : runs)
    v.push_back(field(t));
  return median(v);
}

void printHeader()
{
  std::printf(
      "| threads, target | total | target prep | sampling | SO(3) | refinement | "
      "translation | verification | other | minor page faults |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
}

void printRow(const char* label, const std::vector<Timing>& runs, double unit)
{
  using T = const Timing&;
  const auto cell = [&](auto field) {
    const double ms = medianOf(runs, field);
    std::printf(" %.1f / %.2f |", ms, ms / unit);
  };
  std::printf("| %s |", label);
  cell([](T t) { return t.ms; });
  cell([](T t) { return t.stages.target; });
  cell([](T t) { return t.stages.sampling + t.stages.sht; });
  cell([](T t) { return t.stages.so3 + t.stages.orientation; });
  cell([](T t) { return t.stages.refinement; });
  cell([](T t) { return t.stages.translation; });
  cell([](T t) { return t.stages.verification; });
  cell([](T t) { return t.ms - t.stages.total(); });
  std::printf(" %.0f |\n", medianOf(runs, [](T t) { return double(t.faults); }));
}

/** Median ratio, over consecutive pairs, of two aligns in two threads (1 engine thread
 *  each) to the same two aligns in series. */
double twoThreadsRatio(const std::vector<Pair>& pairs)
{
  const auto alignOnce = [](const Pair& p) {
    pcl::PhaserRegistration<PointT, PointT> phaser;
    phaser.setNumberOfThreads(1);
    phaser.setInputSource(p.source);
    phaser.setInputTarget(p.target);
    Cloud out;
    phaser.align(out);
  };
  std::vector<double> ratios;
  for (std::size_t k = 0; k + 1 < pairs.size(); k += 2) {
    auto start = Clock::now();
    alignOnce(pairs[k]);
    alignOnce(pairs[k + 1]);
    const double serial = msSince(start);
    start = Clock::now();
    std::thread other([&] { alignOnce(pairs[k + 1]); });
    alignOnce(pairs[k]);
    other.join();
    ratios.push_back(msSince(start) / serial);
  }
  return median(ratios);
}

/** A fresh align of \a p with 2 engine threads and \a channels; its result. */
Timing alignWithChannels(const Pair& p, std::uint32_t channels,
                         pcl::phaser::PhaserResult& result)
{
  pcl::PhaserRegistration<PointT, PointT> phaser;
  pcl::phaser::PhaserParameters params;
  params.num_threads = 2;
  params.channels = channels;
  phaser.setParameters(params);
  phaser.setInputSource(p.source);
  phaser.setInputTarget(p.target);
  const Timing timing = timedAlign(phaser);
  result = phaser.getResult();
  return timing;
}

/** Fused against range-only aligns, alternated per pair: their stages, the median time
 *  ratio and the pairs whose estimate or claim differs (over 0.05 deg or 1 cm). */
void compareFusion(const std::vector<Pair>& pairs, double unit)
{
  std::vector<Timing> fused_runs, range_runs;
  std::vector<double> ratios;
  int moved = 0, claims = 0;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    pcl::phaser::PhaserResult fused, range;
    if (k % 2 == 1)
      range_runs.push_back(
          alignWithChannels(pairs[k], pcl::phaser::CHANNEL_RANGE, range));
    fused_runs.push_back(alignWithChannels(pairs[k], ~0u, fused));
    if (k % 2 == 0)
      range_runs.push_back(
          alignWithChannels(pairs[k], pcl::phaser::CHANNEL_RANGE, range));
    ratios.push_back(fused_runs.back().ms / range_runs.back().ms);
    const Eigen::Matrix4d d = fused.transformation.inverse() * range.transformation;
    const double deg = Eigen::AngleAxisd(d.topLeftCorner<3, 3>()).angle() * 180 / M_PI;
    moved += deg > 0.05 || d.topRightCorner<3, 1>().norm() > 0.01;
    claims += fused.converged != range.converged;
  }
  std::printf(
      "\nFused (range and intensity, the default) against range only (channels = "
      "range), alternated per pair:\n\n");
  printHeader();
  printRow("2, fresh, fused", fused_runs, unit);
  printRow("2, fresh, range only", range_runs, unit);
  std::printf(
      "\nfused / range only (median over the pairs): %.3f; estimates apart (over "
      "0.05 deg or 1 cm) on %d of %zu pairs, claims differ on %d\n",
      median(ratios), moved, pairs.size(), claims);
}

/** The aligns of the pairs: the stage table, the thread figures and the fusion
 *  comparison (that alone with --fusion). */
int runSpeed(BenchArguments& args)
{
  const int max_pairs = static_cast<int>(args.integer("--max-pairs", 0));
  const std::string file =
      args.text("--pairs-file", args.data() + "/lidar/balm_handheld/pairs.txt");
  if (!args.ok())
    return args.fail();
  std::vector<Pair> pairs;
  if (!loadPairs(file, max_pairs, pairs))
    return 0;
  const double before = pcl::phaser::bench::fftYardstickMs();
  {
    std::vector<Timing> warm, unused;
    timePairs({pairs.front()}, 2, warm, unused); // tables, plans, pool
  }
  if (args.has("--fusion")) {
    compareFusion(pairs, before);
    return 0;
  }
  std::vector<Timing> fresh[2], cached[2];
  for (int threads : {1, 2})
    timePairs(pairs, threads, fresh[threads - 1], cached[threads - 1]);
  const double ratio = twoThreadsRatio(pairs);
  const double after = pcl::phaser::bench::fftYardstickMs();
  const double unit = 0.5 * (before + after);
  std::printf("%zu revisit pairs of %s, defaults (PointXYZI, intensity fused), warm "
              "process. Yardstick: one 128^3 r2c FFT (1 thread) = %.2f ms before, %.2f "
              "ms after (units: their mean).\nMedians over the pairs, ms / FFT units; "
              "SO(3) includes the orientation histograms, sampling the SHT.\n\n",
              pairs.size(), file.c_str(), before, after);
  printHeader();
  printRow("1, fresh", fresh[0], unit);
  printRow("1, cached", cached[0], unit);
  printRow("2, fresh", fresh[1], unit);
  printRow("2, cached", cached[1], unit);
  std::vector<double> speedup;
  for (std::size_t k = 0; k < pairs.size(); ++k)
    speedup.push_back(fresh[0][k].ms / fresh[1][k].ms);
  std::printf("\n2 threads against 1 (fresh, median over the pairs): %.2fx faster\n"
              "two aligns in two threads of one process (1 engine thread each) / the "
              "same two in series (median over %zu couples): %.2f\n",
              median(speedup), pairs.size() / 2, ratio);
  compareFusion(pairs, unit);
  return 0;
}

} // namespace

const pcl::phaser::bench::Subcommand pcl::phaser::bench::kSpeed = {
    "speed",
    "the time of aligns of the revisit pairs in a warm process: fresh and cached, "
    "1 and 2 threads, by stage; two aligns in two threads; fused against range "
    "only",
    nullptr,
    {sharedOption("--data"),
     sharedOption("--pairs-file"),
     sharedOption("--max-pairs"),
     {"--fusion", nullptr, "the fused against range-only comparison alone"}},
    false,
    0,
    runSpeed};
