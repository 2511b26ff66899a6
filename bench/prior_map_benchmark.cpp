/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_prior_map_benchmark: relocalization in a prior map aggregated from the
 * balm_handheld scans (every second listed scan from scan 0, optionally voxel-thinned),
 * kept in scan 0's frame or moved rigidly to site frames whose origins lie far from
 * the data; the other scans are the queries. Default parameters, one target prepared
 * once per frame.
 *
 *   pcl_phaser_prior_map_benchmark [-data DIR] [-every 2] [-voxel 0.1]
 *                                  [-distances 0,200,5000] [-queries 15] [-threads 2]
 *
 * Prints per query the errors against site * T_world_query, converged and the align
 * time; per frame the map's points, the target's preparation (ms), the median query
 * (ms, preparation excluded), right (5 deg / 0.6 m) and converged counts, and the
 * process's peak resident memory; times also in FFT units (one 128^3 r2c FFT on one
 * thread, measured first).
 */
#include "fft_yardstick.h"
#include "prior_map.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/console/parse.h>

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
bool runFrame(const std::string& dir, const PriorMap& map, int queries, int threads,
              double fft_ms)
{
  pcl::PhaserRegistration<pcl::PointXYZI, pcl::PointXYZI> phaser;
  phaser.setNumberOfThreads(static_cast<unsigned>(threads));
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

} // namespace

int main(int argc, char** argv)
{
  std::string dir = "../shared/data";
  int every = 2, queries = 15, threads = 2;
  double voxel = 0.1;
  std::vector<double> distances{0.0, 200.0, 5000.0};
  pcl::console::parse_argument(argc, argv, "-data", dir);
  pcl::console::parse_argument(argc, argv, "-every", every);
  pcl::console::parse_argument(argc, argv, "-voxel", voxel);
  pcl::console::parse_argument(argc, argv, "-queries", queries);
  pcl::console::parse_argument(argc, argv, "-threads", threads);
  pcl::console::parse_x_arguments(argc, argv, "-distances", distances);
  if (every < 2 || queries < 1 || threads < 1) {
    std::fprintf(stderr,
                 "prior_map: -every must be >= 2, -queries and -threads >= 1\n");
    return 1;
  }
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
    if (!runFrame(dir, map, queries, threads, fft_ms))
      return 1;
  }
  return 0;
}
