/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_bench region: queries against an unthinned prior map of the shared
 * handheld scans with a position prior and without, against a scan-to-scan align of
 * the same query onto the nearest map scan (doc/benchmarks.md, *Position prior*).
 */
#include "bench_timing.h"
#include "fft_yardstick.h"
#include "prior_map.h"
#include "subcommands.h"

#include <pcl_phaser/core/pipeline.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using namespace pcl::phaser;

/** The engine's view of a PCL cloud: points and intensity. */
SourceCloud toEngine(const pcl::PointCloud<pcl::PointXYZI>& cloud)
{
  SourceCloud out;
  out.points.resize(3, static_cast<Eigen::Index>(cloud.size()));
  out.channels.assign(1, Eigen::VectorXd(static_cast<Eigen::Index>(cloud.size())));
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    out.points.col(i) = cloud[i].getVector3fMap().cast<double>();
    out.channels[0](i) = cloud[i].intensity;
  }
  return out;
}

/** Scan \a index of \a dir in its sensor frame (empty when unreadable). */
SourceCloud scanOf(const std::string& dir, int index)
{
  std::string error;
  const auto cloud = bench::readScan(dir, index, error);
  if (!cloud)
    std::fprintf(stderr, "%s\n", error.c_str());
  return cloud ? toEngine(*cloud) : SourceCloud();
}

struct Timed {
  double ms = 0.0;
  PhaserResult result;
};

Timed timedAlign(const Target& target, const SourceCloud& source,
                 const PhaserParameters& params)
{
  const auto start = bench::Clock::now();
  Timed t;
  t.result = align(target, source, Eigen::Matrix4d::Identity(), params);
  t.ms = bench::msSince(start);
  return t;
}

/** The median time of \a runs aligns; \a vary(k) sets the parameters of run k. */
template <typename Vary>
Timed medianOf(int runs, const Target& target, const SourceCloud& source,
               PhaserParameters params, const Vary& vary)
{
  std::vector<Timed> all;
  for (int k = 0; k < runs; ++k) {
    vary(params, k);
    all.push_back(timedAlign(target, source, params));
  }
  std::sort(all.begin(), all.end(),
            [](const Timed& a, const Timed& b) { return a.ms < b.ms; });
  return all[all.size() / 2];
}

/** "converged rotation-error-deg translation-error-m" of \a result against \a truth. */
std::string verdict(const PhaserResult& result, const Eigen::Matrix4d& truth)
{
  const Eigen::Matrix3d d = result.transformation.topLeftCorner<3, 3>().transpose() *
                            truth.topLeftCorner<3, 3>();
  const StageTimes& t = result.diagnostics.times;
  char text[160];
  std::snprintf(
      text, sizeof(text),
      "%s %.2f deg %.3f m (%zu hyp.; so3 %.0f, tr. %.0f, ver. %.0f ms)",
      result.converged ? "yes" : "no ", Eigen::AngleAxisd(d).angle() * 180.0 / M_PI,
      (result.transformation - truth).topRightCorner<3, 1>().norm(),
      result.diagnostics.hypotheses.size(), t.so3, t.translation, t.verification);
  return text;
}

/** The map scan nearest to scan \a index, as a Target in its own frame. */
Target nearestScan(const bench::PriorMap& m, const std::string& dir, int index,
                   int& nearest, Eigen::Matrix4d& world_nearest)
{
  const Eigen::Vector3d at = m.world_lidar.at(index).topRightCorner<3, 1>();
  double best = HUGE_VAL;
  for (int k : m.in_map) {
    const double d = (m.world_lidar.at(k).topRightCorner<3, 1>() - at).norm();
    if (d < best) {
      best = d;
      nearest = k;
      world_nearest = m.world_lidar.at(k);
    }
  }
  SourceCloud scan = scanOf(dir, nearest);
  return Target(std::move(scan.points), std::move(scan.channels));
}

void runQuery(const bench::PriorMap& m, const Target& map, const std::string& dir,
              int index, double radius, int runs, const PhaserParameters& engine,
              double unit)
{
  const SourceCloud query = scanOf(dir, index);
  const Eigen::Matrix4d truth = m.world_lidar.at(index);
  int nearest = 0;
  Eigen::Matrix4d world_nearest = Eigen::Matrix4d::Identity();
  const Target scan = nearestScan(m, dir, index, nearest, world_nearest);
  PhaserParameters params = engine;
  params.region.reset();
  const auto same = [](PhaserParameters&, int) {};
  timedAlign(scan, query, params); // prepares the scan target
  const Timed pair = medianOf(runs, scan, query, params, same);
  const Eigen::Vector3d center =
      truth.topRightCorner<3, 1>() + Eigen::Vector3d(3, -4, 0);
  params.region = pcl::phaser::Region{center.x(), center.y(), center.z(), radius};
  // A region moved by a millimeter per run: the map is cropped and prepared each time.
  const Timed fresh =
      medianOf(runs, map, query, params, [&](PhaserParameters& p, int k) {
        p.region->x = center.x() + 1e-3 * (k + 1);
      });
  const Timed cached = medianOf(runs, map, query, params, same);
  PhaserParameters whole = engine;
  whole.region.reset();
  timedAlign(map, query, whole); // prepares the whole map
  const Timed whole_map = medianOf(runs, map, query, whole, same);
  std::printf("| %d | %d | %.1f / %.1f | %s | %.1f / %.2f | %s | %.1f / %.1f | %.2f / "
              "%.2f | %.1f / %.2f | %s |\n",
              index, nearest, pair.ms, pair.ms / unit,
              verdict(pair.result, world_nearest.inverse() * truth).c_str(), fresh.ms,
              fresh.ms / pair.ms, verdict(cached.result, truth).c_str(), cached.ms,
              cached.ms / unit, fresh.result.diagnostics.times.target / unit,
              cached.ms / pair.ms, whole_map.ms, whole_map.ms / pair.ms,
              verdict(whole_map.result, truth).c_str());
}

/** The map, then each query's row. */
int runRegion(bench::BenchArguments& args)
{
  const std::string dir = args.data() + "/lidar/balm_handheld";
  const int every = static_cast<int>(args.integer("--every", 2));
  const int runs = static_cast<int>(args.integer("--runs", 5));
  const double radius = args.number("--radius", 10.0);
  const PhaserParameters engine = args.engine(2);
  const int threads = engine.num_threads;
  std::vector<int> queries;
  for (const std::string& q : args.files()) {
    long index = 0;
    args.check(parseInteger(q, 0, 1 << 20, index), "Invalid query index '" + q + "'");
    queries.push_back(static_cast<int>(index));
  }
  if (queries.empty())
    queries = {6, 90, 150};
  args.check(every >= 2 && runs >= 1 && radius > 0.0,
             "expected --every >= 2, --runs >= 1, --radius > 0");
  if (!args.ok())
    return args.fail();
  const double unit = bench::fftYardstickMs();
  bench::PriorMap m;
  std::string error;
  if (!bench::buildPriorMap(dir, every, 0.0, Eigen::Matrix4d::Identity(), m, error)) {
    std::fprintf(stderr, "cannot build the map: %s\n", error.c_str());
    return 2;
  }
  SourceCloud points = toEngine(*m.cloud);
  const Target map(std::move(points.points), std::move(points.channels));
  std::printf(
      "map: every %d-th listed scan of %s, %ld points; %d threads, median of %d; "
      "region radius %.0f m about a point 5 m from the truth; yardstick: one "
      "128^3 r2c FFT (1 thread) = %.2f ms\n\n",
      every, dir.c_str(), static_cast<long>(map.points().cols()), threads, runs, radius,
      unit);
  std::printf(
      "| query | nearest map scan | scan pair ms / units | scan pair: converged, "
      "errors | region, new: ms / x pair | region: converged, errors | region, "
      "cached: ms / units | region preparation units / cached x pair | whole map "
      "ms / x pair | whole map: converged, errors |\n|---|---|---|---|---|---|---|"
      "---|---|---|\n");
  for (int index : queries) {
    if (std::find(m.queries.begin(), m.queries.end(), index) == m.queries.end()) {
      std::fprintf(stderr, "scan %d: not a query (no pose, or in the map)\n", index);
      return 1;
    }
    runQuery(m, map, dir, index, radius, runs, engine, unit);
  }
  return 0;
}

} // namespace

const pcl::phaser::bench::Subcommand pcl::phaser::bench::kRegion = {
    "region",
    "queries against an unthinned prior map with a position prior (a region of "
    "radius R about a point 5 m from the truth), without, and against the nearest "
    "map scan",
    "[QUERY_INDEX ...]",
    {sharedOption("--data"),
     {"--every", "K", "every K-th listed scan in the map (default 2)"},
     {"--radius", "R", "the region's radius (m; default 10)"},
     {"--runs", "N", "aligns per figure, the median printed (default 5)"}},
    true,
    2,
    runRegion};
