/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The aligners pcl_phaser_bench compares, behind one signature: pcl_phaser (fused
 * and range-only), PCL's global aligners (SAC-IA and SampleConsensusPrerejective on
 * FPFH, FPCS, KFPCS) and its local ones started from identity (ICP, GICP, NDT).
 */
#pragma once

#include "protocol.h"

#include <pcl_phaser/core/parameters.h>
#include <pcl_phaser/core/result.h>

#include <Eigen/Core>

#include <chrono>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pcl::phaser {
namespace bench {

/** \brief What a method may be tuned with; scale-dependent radii derive from voxel. */
struct MethodSettings {
  double voxel = 0.5;    ///< leaf of the downsampling for PCL's methods (m)
  bool centroid = false; ///< pcl_phaser: project about the centroids (overrides engine)
  int threads = 2;
  int bandwidth = 64;    ///< pcl_phaser spherical bandwidth
  unsigned seed = 1;     ///< std::srand seed of PCL's randomized aligners
  int fpcs_seconds = 10; ///< time limit of FPCS / KFPCS
  /** pcl_phaser's setNormalizedRefinement (false: off whatever engine says) */
  bool normalized_refinement = true;
  /** pcl_phaser's other settings (--orientation-candidates, --max-tilt, ...); its
   *  bandwidth and threads are the two above */
  PhaserParameters engine;
};

/** \brief A method's time by stage, in the order it runs them: (name, ms). */
using StageList = std::vector<std::pair<std::string, double>>;

/** \brief One registration's outcome (T maps the source into the target frame). */
struct MethodResult {
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();
  bool converged = false;
  double ms = 0.0;
  /** the method's own quality figure: pcl_phaser's translation peak score, else
   * PCL's fitness score (mean squared distance, m^2) */
  double score = std::numeric_limits<double>::quiet_NaN();
  /** pcl_phaser's result without its lists (hypotheses, rotation samples): the CSV's
   *  result columns (result_csv.h); none for other methods */
  std::optional<PhaserResult> phaser;
  /** the stages of ms: pcl_phaser's diagnostics.times (visitStageTimes() names), the
   *  FPFH aligners' "features" (downsampling, normals and FPFH of both clouds) and
   *  "search" (align()); empty for the other methods. Their sum is at most ms. */
  StageList stages;
  bool has_covariance = false;
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
};

/** \brief How a method's covariance covers its pose error, -1 (and sigmas 0) without a
 * covariance or when a block is not positive definite. The error is ordered as
 * pcl::phaser::poseCovariance orders it: omega = Log(R_true R_est^T) [rad], then nu =
 * t_true - t_est [m]. Chi-square: 6 dof for the 6-D NEES (mean 6, 95 % below 12.59), 3
 * dof for each block (mean 3, 95 % below 7.81). */
struct NeesFigures {
  double nees = -1.0;         ///< 6-D
  double nees_rot = -1.0;     ///< the rotation error under the rotation block
  double nees_trans = -1.0;   ///< the translation error under the translation block
  double sigma_rot_deg = 0.0; ///< sqrt(trace) of the rotation block
  double sigma_trans_m = 0.0; ///< sqrt(trace) of the translation block
};

/** \brief The NEES of \a r's pose against \a truth (T_target_source) under
 * r.covariance; all -1 when r.has_covariance is false. */
NeesFigures neesOf(const MethodResult& r, const Eigen::Matrix4d& truth);

/** \brief One method's registration of one pair judged against the pair's truth: what
 *  every study records (compare's Trial, revisits' and objects' trials extend it). */
struct Judged {
  std::string method; ///< e.g. "phaser", "sacia+icp"
  double rre = 0.0;   ///< rotation error (deg), rreDeg()
  double rte = 0.0;   ///< translation error (m), rteM()
  double ms = 0.0;
  bool converged = false; ///< the method's own verdict
  bool success = false;   ///< under the study's thresholds (set by the study)
  double score = 0.0;     ///< the method's quality figure (see MethodResult)
  NeesFigures nees;       ///< under the method's covariance, -1 without one
  Eigen::Matrix4d estimate = Eigen::Matrix4d::Identity(); ///< T_target_source
  std::optional<PhaserResult> phaser; ///< pcl_phaser's result (MethodResult)
  StageList stages;                   ///< the method's stages (MethodResult)
};

/** \brief \a r of \a method judged against \a truth (T_target_source): errors, NEES,
 *  the rest copied; success left false. */
Judged judge(const std::string& method, const MethodResult& r,
             const Eigen::Matrix4d& truth);

using MethodFunction =
    std::function<MethodResult(const Cloud::ConstPtr& source,
                               const Cloud::ConstPtr& target, const MethodSettings&)>;

struct Method {
  std::string name;
  bool global = true; ///< false for the local methods started from identity
  MethodFunction run;
};

/** \brief All methods, in table order: phaser, phaser_xyz, phaser_plain (fused, plain
 * rotation refinement), sacia, prerejective, fpcs,
 * kfpcs, icp, gicp, ndt. */
const std::vector<Method>& allMethods();

/** \brief The method of allMethods() called \a name, or null. */
const Method* findMethod(const std::string& name);

/** \brief The settings a study starts from: \a engine (and its threads for every
 *  method), PCL's leaf \a voxel, \a seed and the FPCS time limit \a fpcs_seconds. */
MethodSettings studySettings(const PhaserParameters& engine, double voxel,
                             unsigned seed, int fpcs_seconds);

/** \brief pcl::IterativeClosestPoint from \a initial on clouds downsampled at
 * settings.voxel; max correspondence distance 2 voxels, 50 iterations. The time of the
 * refinement is added to result.ms; converged stays as the initial method said. */
void refineWithIcp(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                   const MethodSettings& settings, MethodResult& result);

// Per-family entry points (methods_*.cpp).
MethodResult runPhaser(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                       const MethodSettings& settings, bool fuse_intensity);
MethodResult runSacIa(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                      const MethodSettings& settings);
MethodResult runPrerejective(const Cloud::ConstPtr& source,
                             const Cloud::ConstPtr& target,
                             const MethodSettings& settings);
MethodResult runFpcs(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                     const MethodSettings& settings, bool keypoint_variant);
MethodResult runIcp(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                    const MethodSettings& settings);
MethodResult runGicp(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                     const MethodSettings& settings);
MethodResult runNdt(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                    const MethodSettings& settings);

/** \brief xyz of \a cloud downsampled with a voxel grid of leaf \a voxel (no
 * downsampling when voxel <= 0). */
pcl::PointCloud<pcl::PointXYZ>::Ptr downsampleXYZ(const Cloud& cloud, double voxel);

/** \brief A scan read with pcl::phaser::loadCloud, non-finite points removed; null (and
 * the reason printed with PCL's console) when it cannot be read. */
Cloud::Ptr loadFiniteScan(const std::string& path);

/** \brief Milliseconds since \a start. */
double elapsedMs(std::chrono::steady_clock::time_point start);

} // namespace bench
} // namespace pcl::phaser
