/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "cloud_reading.h"
#include "methods.h"

#include <pcl/console/print.h>
#include <pcl/filters/filter.h>
#include <pcl/filters/voxel_grid.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include <cmath>

namespace pcl::phaser {
namespace bench {

const std::vector<Method>& allMethods()
{
  static const std::vector<Method> methods = {
      {"phaser", true,
       [](auto s, auto t, const auto& m) { return runPhaser(s, t, m, true); }},
      {"phaser_xyz", true,
       [](auto s, auto t, const auto& m) { return runPhaser(s, t, m, false); }},
      {"phaser_plain", true,
       [](auto s, auto t, const auto& m) {
         MethodSettings plain = m;
         plain.normalized_refinement = false;
         return runPhaser(s, t, plain, true);
       }},
      {"sacia", true, runSacIa},
      {"prerejective", true, runPrerejective},
      {"fpcs", true,
       [](auto s, auto t, const auto& m) { return runFpcs(s, t, m, false); }},
      {"kfpcs", true,
       [](auto s, auto t, const auto& m) { return runFpcs(s, t, m, true); }},
      {"icp", false, runIcp},
      {"gicp", false, runGicp},
      {"ndt", false, runNdt},
  };
  return methods;
}

const Method* findMethod(const std::string& name)
{
  for (const Method& m : allMethods())
    if (m.name == name)
      return &m;
  return nullptr;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr downsampleXYZ(const Cloud& cloud, double voxel)
{
  auto xyz = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::copyPointCloud(cloud, *xyz);
  if (voxel <= 0.0)
    return xyz;
  auto out = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::VoxelGrid<pcl::PointXYZ> grid;
  grid.setLeafSize(static_cast<float>(voxel), static_cast<float>(voxel),
                   static_cast<float>(voxel));
  grid.setInputCloud(xyz);
  grid.filter(*out);
  return out;
}

namespace {

/** e^T C^-1 e, or -1 when C is not positive definite. */
template <int N>
double mahalanobis(const Eigen::Matrix<double, N, 1>& e,
                   const Eigen::Matrix<double, N, N>& C)
{
  const Eigen::LDLT<Eigen::Matrix<double, N, N>> ldlt(C);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() ||
      !(ldlt.vectorD().minCoeff() > 0.0))
    return -1.0;
  return e.dot(ldlt.solve(e));
}

} // namespace

NeesFigures neesOf(const MethodResult& r, const Eigen::Matrix4d& truth)
{
  NeesFigures f;
  if (!r.has_covariance)
    return f;
  Eigen::Matrix<double, 6, 1> e;
  const Eigen::AngleAxisd omega(
      Eigen::Matrix3d(truth.topLeftCorner<3, 3>() *
                      r.transformation.topLeftCorner<3, 3>().transpose()));
  e.head<3>() = omega.angle() * omega.axis();
  e.tail<3>() = truth.topRightCorner<3, 1>() - r.transformation.topRightCorner<3, 1>();
  const Eigen::Matrix3d rot = r.covariance.topLeftCorner<3, 3>();
  const Eigen::Matrix3d trans = r.covariance.bottomRightCorner<3, 3>();
  f.nees = mahalanobis<6>(e, r.covariance);
  f.nees_rot = mahalanobis<3>(Eigen::Vector3d(e.head<3>()), rot);
  f.nees_trans = mahalanobis<3>(Eigen::Vector3d(e.tail<3>()), trans);
  f.sigma_rot_deg = std::sqrt(rot.trace()) * 180.0 / M_PI;
  f.sigma_trans_m = std::sqrt(trans.trace());
  return f;
}

MethodSettings studySettings(const PhaserParameters& engine, double voxel,
                             unsigned seed, int fpcs_seconds)
{
  MethodSettings settings;
  settings.threads = engine.num_threads;
  settings.voxel = voxel;
  settings.seed = seed;
  settings.fpcs_seconds = fpcs_seconds;
  settings.engine = engine;
  return settings;
}

Judged judge(const std::string& method, const MethodResult& r,
             const Eigen::Matrix4d& truth)
{
  Judged j;
  j.method = method;
  j.rre = rreDeg(r.transformation, truth);
  j.rte = rteM(r.transformation, truth);
  j.ms = r.ms;
  j.converged = r.converged;
  j.score = r.score;
  j.nees = neesOf(r, truth);
  j.estimate = r.transformation;
  j.phaser = r.phaser;
  j.stages = r.stages;
  return j;
}

double elapsedMs(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() -
                                                   start)
      .count();
}

Cloud::Ptr loadFiniteScan(const std::string& path)
{
  auto cloud = pcl::make_shared<Cloud>();
  std::string error;
  if (!pcl::phaser::loadCloud(path, *cloud, &error)) {
    pcl::console::print_error("%s\n", error.c_str());
    return nullptr;
  }
  pcl::Indices kept;
  pcl::removeNaNFromPointCloud(*cloud, *cloud, kept);
  return cloud;
}

} // namespace bench
} // namespace pcl::phaser
