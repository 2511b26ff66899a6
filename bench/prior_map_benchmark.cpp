/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_bench prior-map: relocalization in a prior map aggregated from the
 * balm_handheld scans, kept in scan 0's frame or moved rigidly to site frames far from
 * the data; the other scans are the queries. Per query the errors and time, per frame
 * the map's points, the target's preparation, the median query, right and converged
 * counts and the peak resident memory.
 */
#include "fft_yardstick.h"
#include "prior_map.h"
#include "subcommands.h"

#include <pcl_phaser/phaser_registration.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdio>
#include <string>
#include <sys/resource.h>
#include <vector>

namespace {

using pcl::phaser::bench::PriorMap;

/** Peak resident memory of the process, MB. */
double peakRssMb()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

/** The queries against one map; false when a scan cannot be read. */
bool runFrame(const std::string& dir, const PriorMap& map, int queries,
              const pcl::phaser::PhaserParameters& params, double fft_ms)
{
  pcl::PhaserRegistration<pcl::PointXYZI, pcl::PointXYZI> phaser;
  phaser.setParameters(params);
  phaser.setInputTarget(map.cloud);
  std::vector<double> query_ms;
  double prepare_ms = 0.0;
  int right = 0, converged = 0;
  for (int k = 0; k < queries && k < static_cast<int>(map.queries.size()); ++k) {
    const int index = map.queries[static_cast<std::size_t>(k)];
    std::string error;
    const auto scan = pcl::phaser::bench::readScan(dir, index, error);
    if (!scan) {
      std::fprintf(stderr, "prior_map: %s\n", error.c_str());
      return false;
    }
    phaser.setInputSource(scan);
    pcl::PointCloud<pcl::PointXYZI> aligned;
    phaser.align(aligned);
    const pcl::phaser::PhaserResult& r = phaser.getResult();
    const Eigen::Matrix4d truth = map.site * map.world_lidar.at(index);
    const Eigen::Matrix4d T = r.transformation;
    const double rre = Eigen::AngleAxisd(T.topLeftCorner<3, 3>().transpose() *
                                         truth.topLeftCorner<3, 3>())
                           .angle() *
                       180.0 / M_PI;
    const double rte = (T.topRightCorner<3, 1>() - truth.topRightCorner<3, 1>()).norm();
    prepare_ms += r.diagnostics.times.target;
    query_ms.push_back(r.diagnostics.times.total() - r.diagnostics.times.target);
    right += rre < 5.0 && rte < 0.6;
    converged += r.converged;
    std::printf("  full%d.pcd: %.2f deg %.3f m converged %d, %.0f ms\n", index, rre,
                rte, static_cast<int>(r.converged), query_ms.back());
  }
  std::sort(query_ms.begin(), query_ms.end());
  const double median = query_ms.empty() ? 0.0 : query_ms[query_ms.size() / 2];
  std::printf(
      "map %zu points, %.0f m away: prepare %.0f ms (%.1f FFT), query median "
      "%.0f ms (%.1f FFT); right %d / %zu, converged %d / %zu; peak RSS %.0f MB\n",
      map.cloud->size(), map.site.topRightCorner<3, 1>().norm(), prepare_ms,
      prepare_ms / fft_ms, median, median / fft_ms, right, query_ms.size(), converged,
      query_ms.size(), peakRssMb());
  return true;
}

/** The map in each site frame and its queries. */
int runPriorMap(pcl::phaser::bench::BenchArguments& args)
{
  std::string dir = args.data();
  const int every = static_cast<int>(args.integer("--every", 2));
  const int queries = static_cast<int>(args.integer("--queries", 15));
  const double voxel = args.number("--voxel", 0.1);
  const std::vector<double> distances =
      args.numbers("--distances", {0.0, 200.0, 5000.0});
  const pcl::phaser::PhaserParameters params = args.engine(2);
  const int threads = params.num_threads;
  args.check(every >= 2 && queries >= 1 && threads >= 1,
             "--every must be >= 2, --queries and --threads >= 1");
  if (!args.ok())
    return args.fail();
  dir += "/lidar/balm_handheld";
  const double fft_ms = pcl::phaser::bench::fftYardstickMs();
  std::printf("yardstick FFT128 %.2f ms; map: every %d-th scan, voxel %.2f m; %d "
              "threads\n",
              fft_ms, every, voxel, threads);
  for (double distance : distances) {
    PriorMap map;
    std::string error;
    if (!pcl::phaser::bench::buildPriorMap(
            dir, every, voxel, pcl::phaser::bench::siteFrame(distance), map, error)) {
      std::fprintf(stderr, "prior_map: %s\n", error.c_str());
      return 1;
    }
    if (!runFrame(dir, map, queries, params, fft_ms))
      return 1;
  }
  return 0;
}

} // namespace

const pcl::phaser::bench::Subcommand pcl::phaser::bench::kPriorMap = {
    "prior-map",
    "relocalization in a prior map of the handheld scans, in scan 0's frame and "
    "in site frames far from the data",
    nullptr,
    {sharedOption("--data"),
     {"--every", "K", "every K-th listed scan from scan 0 in the map (default 2)"},
     sharedOption("--voxel", "the map's voxel (m; default 0.1, 0: unthinned)"),
     {"--distances", "L", "the site frames' distances (m; default 0,200,5000)"},
     {"--queries", "N", "queries per frame (default 15)"}},
    true,
    2,
    runPriorMap};
