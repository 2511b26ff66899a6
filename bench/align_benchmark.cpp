/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_align_benchmark: time per PhaserRegistration::align on a LiDAR pair at the
 * defaults, with 1 and 2 threads, with a fresh and with a cached target, broken down by
 * stage. Without files it uses the simulated demo pair (64 beams, ~113k points each).
 *
 *   pcl_phaser_align_benchmark [SOURCE TARGET] [-r repetitions] [-b bandwidth]
 *                              [-range_only] [-plain]
 * -range_only switches the intensity channel off, so the two runs show what fusing one
 * extra channel costs per stage; -plain refines the rotation on plain C only, not also
 * on the energy-normalised correlation (setNormalizedRefinement(false)). Timings are
 * wall-clock.
 */
#include "cloud_reading.h"
#include "fft_yardstick.h"
#include "scan_simulator.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/filters/filter.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using PointT = pcl::PointXYZI;
using Cloud = pcl::PointCloud<PointT>;

struct Row {
  double total = 0.0;
  pcl_phaser::PhaserEstimate estimate;
};

/** Median (by total time) of \a reps aligns; \a cached keeps the target model between.
 */
Row measure(const Cloud::Ptr& source, const Cloud::Ptr& target, int threads,
            bool cached, int reps, int bandwidth, bool range_only, bool normalized)
{
  std::vector<Row> rows;
  pcl::PhaserRegistration<PointT, PointT> phaser;
  phaser.setUseIntensity(!range_only);
  phaser.setNormalizedRefinement(normalized);
  phaser.setBandwidth(bandwidth);
  phaser.setNumberOfThreads(threads);
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  Cloud out;
  phaser.align(out); // warm-up: plans and tables, and the target cache when cached
  for (int i = 0; i < reps; ++i) {
    if (!cached)
      phaser.setInputTarget(target);
    const auto start = std::chrono::steady_clock::now();
    phaser.align(out);
    Row r;
    r.total = std::chrono::duration<double, std::milli>(
                  std::chrono::steady_clock::now() - start)
                  .count();
    r.estimate = phaser.getEstimate();
    rows.push_back(r);
  }
  std::sort(rows.begin(), rows.end(),
            [](const Row& a, const Row& b) { return a.total < b.total; });
  return rows[rows.size() / 2];
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

} // namespace

int main(int argc, char** argv)
{
  int reps = 7, bandwidth = 64;
  pcl::console::parse_argument(argc, argv, "-r", reps);
  pcl::console::parse_argument(argc, argv, "-b", bandwidth);
  const bool range_only = pcl::console::find_switch(argc, argv, "-range_only");
  const bool normalized = !pcl::console::find_switch(argc, argv, "-plain");
  if (reps < 1 || bandwidth < 1 || bandwidth > 256) {
    pcl::console::print_error("repetitions must be >= 1 and bandwidth in [1, 256]\n");
    return 1;
  }
  Cloud::Ptr source, target;
  std::string name;
  if (!loadPair(argc, argv, source, target, name))
    return 2;
  const double unit = pcl_phaser::bench::fftYardstickMs();
  std::printf(
      "pair: %s (%zu -> %zu points), bandwidth %d, channels: %s, %s refinement, "
      "median of %d; yardstick: one 128^3 r2c FFT (1 thread) = %.2f ms\n\n",
      name.c_str(), source->size(), target->size(), bandwidth,
      range_only ? "range" : "range + intensity", normalized ? "normalised" : "plain",
      reps, unit);
  std::printf(
      "| threads | target | total ms | total FFT units | target prep | sampling | SHT "
      "| SO(3) corr | refinement | translation | orientation | verification | passes "
      "|\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int threads : {1, 2})
    for (bool cached : {false, true}) {
      const Row r = measure(source, target, threads, cached, reps, bandwidth,
                            range_only, normalized);
      const pcl_phaser::PhaserEstimate& e = r.estimate;
      std::printf(
          "| %d | %s | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f "
          "| %.1f | %d |\n",
          threads, cached ? "cached" : "fresh", r.total, r.total / unit, e.target_ms,
          e.sampling_ms, e.sht_ms, e.so3_ms, e.refinement_ms, e.translation_ms,
          e.orientation_ms, e.verification_ms, e.passes);
      std::fflush(stdout);
    }
  return 0;
}
