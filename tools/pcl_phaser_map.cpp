/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_map: a prior map from scans and their poses (the --scans / --poses lists
 * of pcl_phaser_batch), thinned to one point per voxel, for relocalization queries
 * (pcl_phaser_align --region, pcl_phaser_batch --region).
 */
#include "batch_pairs.h"
#include "cloud_reading.h"
#include "engine_options.h"
#include "map_builder.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

constexpr int kUsage = 1, kInput = 2, kOutput = 3;

int usage(const char* name)
{
  std::fprintf(
      stderr,
      "Syntax: %s SCANS POSES OUT.pcd [--voxel V]\n"
      "  SCANS: one scan path per line (relative to its folder); POSES: one "
      "row-major 3x4\n"
      "  T_world_scan per scan (the last 12 numbers of a line). Writes the "
      "scans moved into the\n"
      "  world frame as one binary PCD (x y z intensity), one point (the mean) "
      "per V m cube\n"
      "  (default 0.1; 0: every point). Exit codes: 0 done, 1 usage, 2 "
      "unreadable input, 3 output.\n",
      name);
  return kUsage;
}

} // namespace

int main(int argc, char** argv)
{
  pcl::phaser::CommandLine line;
  std::string error =
      pcl::phaser::collectArguments(argc, argv, {}, {"--voxel"}, line, false);
  double voxel = 0.1;
  std::string text;
  if (error.empty() && line.files.size() != 3)
    error = "expected SCANS, POSES and OUT.pcd";
  else if (error.empty() && line.value("--voxel", text)) {
    if (!pcl::phaser::parseNumber(text, voxel) || !(voxel >= 0.0))
      error = "Invalid --voxel '" + text + "': expected meters >= 0";
  }
  if (!error.empty())
    return std::fprintf(stderr, "Error: %s\n", error.c_str()), usage(argv[0]);
  const std::string& scans = line.files[0];
  const std::string& poses_file = line.files[1];
  const std::string& out = line.files[2];
  std::vector<std::string> names, paths;
  std::vector<Eigen::Matrix4d> poses;
  error = pcl::phaser::batch::readTrajectory(scans, poses_file, names, paths, poses);
  if (!error.empty())
    return std::fprintf(stderr, "Error: %s\n", error.c_str()), kInput;
  pcl::phaser::MapBuilder map(voxel);
  std::size_t read = 0;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    pcl::PointCloud<pcl::PointXYZI> scan;
    if (!pcl::phaser::loadCloud(paths[i], scan, &error))
      return std::fprintf(stderr, "Error: %s\n", error.c_str()), kInput;
    read += scan.size();
    map.add(scan, poses[i]);
  }
  const auto cloud = map.cloud();
  if (!pcl::phaser::saveCloud(out, *cloud, &error))
    return std::fprintf(stderr, "Error: %s\n", error.c_str()), kOutput;
  std::printf("%zu scans, %zu points -> %zu map points (voxel %g m): %s\n",
              paths.size(), read, cloud->size(), voxel, out.c_str());
  return 0;
}
