/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_bench calibrate-covariance: registers simulated LiDAR pairs (makeDemoPair,
 * exact truth) and prints, per pair and bandwidth, the pose error and the ingredients
 * of getCovariance() as CSV. kRotationModelErrorScale (peak_neighborhood.h) was fitted
 * on this output, so that the real scans of pcl_phaser_bench nees stay held out.
 */
#include "cloud_reading.h"
#include "methods.h"
#include "protocol.h"
#include "scan_simulator.h"
#include "subcommands.h"
#include "uncertainty/peak_neighborhood.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>
#include <pcl/filters/filter.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace {

void printMatrix(const Eigen::Matrix3d& m)
{
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      std::printf(",%.6e", m(i, j));
}

/** Centroid of the points, or of the occupied cells of size \a cell when > 0. */
Eigen::Vector3d centroid(const pcl::PointCloud<pcl::PointXYZI>& cloud, double cell)
{
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::set<std::tuple<long, long, long>> seen;
  for (const auto& p : cloud) {
    const Eigen::Vector3d q(p.x, p.y, p.z);
    if (cell > 0.0) {
      const auto key = std::make_tuple(static_cast<long>(std::floor(q.x() / cell)),
                                       static_cast<long>(std::floor(q.y() / cell)),
                                       static_cast<long>(std::floor(q.z() / cell)));
      if (!seen.insert(key).second)
        continue;
      sum += Eigen::Vector3d(std::get<0>(key) + 0.5, std::get<1>(key) + 0.5,
                             std::get<2>(key) + 0.5) *
             cell;
    } else
      sum += q;
  }
  return sum / static_cast<double>(cell > 0.0 ? seen.size() : cloud.size());
}

/** The command line: --seeds N, --bandwidths B1,B2,..., --scan FILE. */
struct Arguments {
  int seeds = 30;
  std::vector<int> bandwidths;
  std::string scan_path;
};

/** The pair of \a seed: with a \a scan, the scan seen again from a random pose drawn
 *  from \a rng with PSNR 50 dB noise; otherwise makeDemoPair(seed). */
pcl::phaser::ScanPair makePair(const pcl::PointCloud<pcl::PointXYZI>::Ptr& scan,
                               int seed, std::mt19937& rng)
{
  if (!scan)
    return pcl::phaser::makeDemoPair(static_cast<unsigned>(seed));
  pcl::phaser::ScanPair pair;
  const Eigen::Matrix4d T = pcl::phaser::bench::randomPose(rng, 2.0);
  pcl::PointCloud<pcl::PointXYZI> perturbed = *scan;
  pcl::phaser::bench::Condition noise;
  pcl::phaser::bench::parseCondition("noise:50", noise);
  pcl::phaser::bench::applyCondition(noise, perturbed, rng);
  pcl::transformPointCloud(perturbed, pair.source, Eigen::Matrix4d(T.inverse()));
  pair.target = *scan;
  pair.T_target_source = T;
  return pair;
}

/** Registers \a source to \a target at bandwidth \a b and prints the CSV row: the
 *  errors against \a truth, the two covariances and the rotated source centroids. */
void registerAndPrint(int seed, int b, const Eigen::Matrix4d& truth,
                      const pcl::PointCloud<pcl::PointXYZI>::Ptr& source,
                      const pcl::PointCloud<pcl::PointXYZI>::Ptr& target)
{
  pcl::PhaserRegistration<pcl::PointXYZI, pcl::PointXYZI> phaser;
  phaser.setBandwidth(b);
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  pcl::PointCloud<pcl::PointXYZI> aligned;
  phaser.align(aligned);
  const Eigen::Matrix4d T = phaser.getFinalTransformation().cast<double>();
  const Eigen::AngleAxisd omega(Eigen::Matrix3d(truth.topLeftCorner<3, 3>() *
                                                T.topLeftCorner<3, 3>().transpose()));
  const Eigen::Vector3d e = omega.angle() * omega.axis();
  const Eigen::Vector3d nu = truth.topRightCorner<3, 1>() - T.topRightCorner<3, 1>();
  std::printf("%d,%d,%d,%.3f,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e", seed, b,
              phaser.hasConverged() ? 1 : 0,
              phaser.getResult().diagnostics.translation_score, e.x(), e.y(), e.z(),
              nu.x(), nu.y(), nu.z());
  printMatrix(phaser.getRotationUncertainty().tangentCovariance());
  printMatrix(phaser.getResult().translation_covariance);
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const Eigen::Vector3d pc = R * centroid(*source, 0.0),
                        v1 = R * centroid(*source, 1.0),
                        v4 = R * centroid(*source, 4.0);
  std::printf(",%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", pc.x(), pc.y(), pc.z(),
              v1.x(), v1.y(), v1.z(), v4.x(), v4.y(), v4.z());
  std::fflush(stdout);
}

/** The CSV header, then a row per pair and bandwidth. */
int runCalibration(pcl::phaser::bench::BenchArguments& args)
{
  Arguments a;
  a.seeds = static_cast<int>(args.integer("--seeds", 30));
  a.scan_path = args.text("--scan");
  for (double b : args.numbers("--bandwidths", {32, 64, 128}))
    if (args.check(b == std::floor(b) && b >= 2 && b <= 256,
                   "--bandwidths: integers in 2..256"))
      a.bandwidths.push_back(static_cast<int>(b));
  if (!args.ok())
    return args.fail();
  std::printf("seed,bandwidth,converged,score,ex,ey,ez,tx,ty,tz,"
              "r00,r01,r02,r11,r12,r22,t00,t01,t02,t11,t12,t22,"
              "px,py,pz,v1x,v1y,v1z,v4x,v4y,v4z\n");
  pcl::PointCloud<pcl::PointXYZI>::Ptr scan;
  if (!a.scan_path.empty() && !(scan = pcl::phaser::bench::loadFiniteScan(a.scan_path)))
    return 2; // the loader said why
  std::mt19937 rng(1);
  for (int seed = 1; seed <= a.seeds; ++seed) {
    const pcl::phaser::ScanPair pair = makePair(scan, seed, rng);
    auto source = pcl::make_shared<pcl::PointCloud<pcl::PointXYZI>>(pair.source);
    auto target = pcl::make_shared<pcl::PointCloud<pcl::PointXYZI>>(pair.target);
    for (int b : a.bandwidths)
      registerAndPrint(seed, b, pair.T_target_source, source, target);
  }
  return 0;
}

} // namespace

const pcl::phaser::bench::Subcommand pcl::phaser::bench::kCalibrateCovariance = {
    "calibrate-covariance",
    "simulated LiDAR pairs registered per bandwidth: the pose errors and the "
    "ingredients of getCovariance() as CSV",
    nullptr,
    {{"--seeds", "N", "pairs, seeds 1..N (default 30)"},
     {"--bandwidths", "L", "bandwidths (default 32,64,128)"},
     {"--scan", "FILE",
      "instead of makeDemoPair: the scan seen again from random poses, 50 dB "
      "noise"}},
    false,
    0,
    runCalibration};
