/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Real scans from ../shared/data (skipped with a message when absent):
 *  - a scan seen again from 20 random poses (uniform rotation, translation up to 2 m),
 *    recovered by the global stage alone, then by ICP started from it;
 *  - real pairs against their reference poses;
 *  - the consistency of getCovariance() on KITTI at PSNR 50 dB.
 */
#include "../registration/test_data.h"
#include "cloud_reading.h"
#include "protocol.h"
#include "real_data_support.h"
#include "transform_file.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>
#include <pcl/filters/filter.h>
#include <pcl/point_types.h>
#include <pcl/registration/icp.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>

namespace {

using PointT = pcl::PointXYZI;
using Cloud = pcl::PointCloud<PointT>;
constexpr double kDeg = M_PI / 180.0;

Cloud::Ptr load(const std::string& relative)
{
  return pcl::phaser::test::loadFiniteCloud<PointT>(relative);
}

using pcl::phaser::bench::randomPose;

/** RRE (deg) and RTE (m) of estimate \a A against truth \a B. */
double rreDeg(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B)
{
  return pcl::phaser::bench::rreDeg(A, B);
}
double rte(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B)
{
  return pcl::phaser::bench::rteM(A, B);
}

/** \a scan seen from pose \a T (the source is T^-1 \a seen) and registered against
 *  \a scan by \a phaser with 2 threads; returns the source. */
Cloud::Ptr alignSeenFrom(const Cloud& seen, const Cloud::Ptr& scan,
                         const Eigen::Matrix4d& T,
                         pcl::PhaserRegistration<PointT, PointT>& phaser)
{
  auto source = pcl::make_shared<Cloud>();
  pcl::transformPointCloud(seen, *source, Eigen::Matrix4d(T.inverse()));
  phaser.setNumberOfThreads(2);
  phaser.setInputSource(source);
  phaser.setInputTarget(scan);
  Cloud aligned;
  phaser.align(aligned);
  return source;
}

/** The azimuth sector of \a scan about \a center (radians), \a half_width wide to
 *  each side (a wedge of the overlap sweep), seen from the pose T whose top three rows
 *  are \a rows (row-major) and registered against \a scan by \a phaser; returns T. */
Eigen::Matrix4d alignSectorSeenFrom(const Cloud::Ptr& scan, double center,
                                    double half_width,
                                    const std::array<double, 12>& rows,
                                    pcl::PhaserRegistration<PointT, PointT>& phaser)
{
  Cloud sector = *scan;
  pcl::phaser::bench::keepSector(sector, center, half_width);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  for (int k = 0; k < 12; ++k)
    T(k / 4, k % 4) = rows[static_cast<std::size_t>(k)];
  alignSeenFrom(sector, scan, T, phaser);
  return T;
}

/** The pose \a phaser found against the truth \a T: printed, within 2 deg / 0.3 m, and
 *  converged. */
void expectRightAndConverged(pcl::PhaserRegistration<PointT, PointT>& phaser,
                             const Eigen::Matrix4d& T)
{
  const Eigen::Matrix4d G = phaser.getFinalTransformation().cast<double>();
  std::printf("  RRE %.3f deg, RTE %.3f m, converged %d, chosen hypothesis %d of %zu\n",
              rreDeg(G, T), rte(G, T), phaser.hasConverged() ? 1 : 0,
              phaser.getResult().chosen_hypothesis,
              phaser.getResult().diagnostics.hypotheses.size());
  EXPECT_LT(rreDeg(G, T), 2.0);
  EXPECT_LT(rte(G, T), 0.3);
  EXPECT_TRUE(phaser.hasConverged());
}

/** \a scan perturbed by \a condition, seen from a random pose T (translation up to
 *  2 m) and registered against \a scan by \a phaser; returns T. */
Eigen::Matrix4d alignPerturbed(const Cloud::Ptr& scan,
                               const pcl::phaser::bench::Condition& condition,
                               std::mt19937& rng,
                               pcl::PhaserRegistration<PointT, PointT>& phaser)
{
  const Eigen::Matrix4d T = randomPose(rng, 2.0);
  Cloud perturbed = *scan;
  pcl::phaser::bench::applyCondition(condition, perturbed, rng);
  alignSeenFrom(perturbed, scan, T, phaser);
  return T;
}

/** The 20-pose protocol of the end-to-end issue. */
void runRandomPoses(const std::string& relative, int poses, unsigned seed)
{
  PCL_PHASER_REQUIRE_DATA(relative);
  const Cloud::Ptr scan = load(relative);
  ASSERT_GT(scan->size(), 1000u);
  std::mt19937 rng(seed);
  int global_ok = 0;
  for (int k = 0; k < poses; ++k) {
    const Eigen::Matrix4d T = randomPose(rng, 2.0);
    pcl::PhaserRegistration<PointT, PointT> phaser;
    const Cloud::Ptr source = alignSeenFrom(*scan, scan, T, phaser);
    const Eigen::Matrix4d G = phaser.getFinalTransformation().cast<double>();
    const double r = rreDeg(G, T), t = rte(G, T);
    const bool ok = phaser.hasConverged() && r < 2.0 && t < 0.3;
    global_ok += ok;
    std::printf("  pose %2d: global RRE %7.3f deg RTE %6.3f m %s", k, r, t,
                ok ? "" : "(miss)");
    if (ok) {
      pcl::IterativeClosestPoint<PointT, PointT> icp;
      icp.setInputSource(source);
      icp.setInputTarget(scan);
      icp.setMaxCorrespondenceDistance(1.0);
      icp.setMaximumIterations(50);
      icp.setTransformationEpsilon(1e-10);
      Cloud aligned;
      icp.align(aligned, phaser.getFinalTransformation());
      const Eigen::Matrix4d I = icp.getFinalTransformation().cast<double>();
      std::printf(" | ICP RRE %.4f deg RTE %.4f m", rreDeg(I, T), rte(I, T));
      EXPECT_LT(rreDeg(I, T), 0.2) << "pose " << k;
      EXPECT_LT(rte(I, T), 0.05) << "pose " << k;
    }
    std::printf("\n");
  }
  EXPECT_GE(global_ok, poses - poses / 20) << relative;
}

} // namespace

TEST(RealScans, Hdl32RandomPoses)
{
  runRandomPoses("lidar/hdl32_fastgicp/251370668.pcd", 20, 1);
}

TEST(RealScans, KittiRandomPoses)
{
  runRandomPoses("lidar/kitti_raw_hdl64/0000000000.bin", 20, 2);
}

TEST(RealScans, KittiSyntheticRandomPoses)
{
  runRandomPoses("lidar/kitti_synthetic_gt/cloud049.ply", 20, 3);
}

// PSNR 40 dB (0.8 m of noise per axis on this downsampled KITTI scan) leaves the
// surfaces thin enough to verify, but every pose, the right one included, puts samples
// in space the target saw through and breaks the free-space limit. Ranked by
// verification, a 180 deg pose whose samples land where the target saw nothing won.
// Now, among poses outside the limits, one that matches less than
// half as much as the best-matching hypothesis ranks below it, and the range peak wins.
TEST(RealScans, HeavyNoiseKeepsTheRangePeak)
{
  const std::string relative = "lidar/kitti_synthetic_gt/cloud049.ply";
  PCL_PHASER_REQUIRE_DATA(relative);
  const Cloud::Ptr scan = load(relative);
  pcl::phaser::bench::Condition noise;
  ASSERT_TRUE(pcl::phaser::bench::parseCondition("noise:40", noise));
  std::mt19937 rng(5);
  int ok = 0;
  const int poses = 5;
  for (int k = 0; k < poses; ++k) {
    pcl::PhaserRegistration<PointT, PointT> phaser;
    const Eigen::Matrix4d T = alignPerturbed(scan, noise, rng, phaser);
    const Eigen::Matrix4d G = phaser.getFinalTransformation().cast<double>();
    std::printf("  pose %d: RRE %7.3f deg RTE %6.3f m\n", k, rreDeg(G, T), rte(G, T));
    ok += rreDeg(G, T) < 5.0 && rte(G, T) < 0.6;
  }
  EXPECT_GE(ok, poses - 1);
}

namespace {

using CloudXYZ = pcl::PointCloud<pcl::PointXYZ>;

CloudXYZ::Ptr loadXYZ(const std::string& relative)
{
  return pcl::phaser::test::loadFiniteCloud<pcl::PointXYZ>(relative);
}

Eigen::Matrix4d fromRows(const double (&r)[12])
{
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  for (int i = 0; i < 12; ++i)
    T(i / 4, i % 4) = r[i];
  return T;
}

/** Mean displacement between a cloud mapped by A and by B: the translation error where
 *  the points are, not at an origin that may lie 100 m away. */
double meanDisplacement(const CloudXYZ& cloud, const Eigen::Matrix4d& A,
                        const Eigen::Matrix4d& B)
{
  double sum = 0.0;
  for (const auto& p : cloud) {
    const Eigen::Vector4d q(p.x, p.y, p.z, 1.0);
    sum += ((A - B) * q).head<3>().norm();
  }
  return sum / static_cast<double>(cloud.size());
}

/** \a source aligned to \a target about their centroids (keypoint and object clouds are
 *  not sensor-centric), with the verification figures printed; \a converged receives
 *  hasConverged(). */
Eigen::Matrix4d alignAboutCentroids(const CloudXYZ::ConstPtr& source,
                                    const CloudXYZ::ConstPtr& target, bool& converged)
{
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
  phaser.setProjectionCenter(decltype(phaser)::ProjectionCenter::Centroid);
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  CloudXYZ out;
  phaser.align(out);
  const pcl::phaser::PhaserResult& e = phaser.getResult();
  std::printf(
      "  global: score %.1f, inliers %.3f, constraint %.3f, samples %d\n",
      e.diagnostics.translation_score, e.diagnostics.verification.inlier_fraction,
      e.diagnostics.verification.constraint, e.diagnostics.verification_samples);
  converged = phaser.hasConverged();
  return phaser.getFinalTransformation().cast<double>();
}

} // namespace

TEST(RealPairs, Hdl32AgainstReference)
{
  PCL_PHASER_REQUIRE_DATA("lidar/hdl32_fastgicp/relative.txt");
  const auto source = loadXYZ("lidar/hdl32_fastgicp/251371071.pcd");
  const auto target = loadXYZ("lidar/hdl32_fastgicp/251370668.pcd");
  Eigen::Matrix4d reference;
  std::string error;
  ASSERT_TRUE(pcl::phaser::loadTransform(
      pcl::phaser::test::dataPath("lidar/hdl32_fastgicp/relative.txt"), reference,
      &error))
      << error;
  // The default center, and ProjectionCenter::Automatic, which must recognize two scans
  // in their sensor frames and give the same answer.
  using Phaser = pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ>;
  for (const auto center :
       {Phaser::ProjectionCenter::SensorOrigin, Phaser::ProjectionCenter::Automatic}) {
    Phaser phaser;
    phaser.setProjectionCenter(center);
    phaser.setInputSource(source);
    phaser.setInputTarget(target);
    CloudXYZ out;
    phaser.align(out);
    ASSERT_TRUE(phaser.hasConverged());
    EXPECT_EQ(phaser.getResult().projection_center,
              Phaser::ProjectionCenter::SensorOrigin);
    const Eigen::Matrix4d G = phaser.getFinalTransformation().cast<double>();
    std::printf("  global: RRE %.3f deg, RTE %.4f m, score %.1f\n",
                rreDeg(G, reference), rte(G, reference),
                phaser.getResult().diagnostics.translation_score);
    EXPECT_LT(rreDeg(G, reference), 1.0);
    EXPECT_LT(rte(G, reference), 0.3);
  }
}

TEST(RealPairs, OfficeKeypointsAgainstGroundTruth)
{
  // PCL's KFPCS test pair: terrestrial scans, partial overlap, ~134 deg yaw; PCL's own
  // tolerance is 0.1745 rad and 1 m. Keypoint clouds are not sensor-centric: centroid
  // mode.
  PCL_PHASER_REQUIRE_DATA("pcl/office2_keypoints.pcd");
  const auto source = loadXYZ("pcl/office1_keypoints.pcd");
  const auto target = loadXYZ("pcl/office2_keypoints.pcd");
  const Eigen::Matrix4d truth =
      fromRows({-0.6946, -0.7194, -0.0051, -3.6352, 0.7194, -0.6945, -0.0100, -2.3865,
                0.0037, -0.0106, 0.9999, 0.7778});
  bool converged = false;
  const Eigen::Matrix4d G = alignAboutCentroids(source, target, converged);
  std::printf("  global: RRE %.3f deg, RTE %.4f m\n", rreDeg(G, truth), rte(G, truth));
  ASSERT_TRUE(converged);
  EXPECT_LT(rreDeg(G, truth) * kDeg, 0.1745);
  EXPECT_LT(rte(G, truth), 1.0);
}

TEST(RealPairs, BunnySacIaPatternWithinIcpBasin)
{
  // PCL's test_sac_ia set-up: bun0 moved by 100 m and yawed by 90 deg, aligned to bun4.
  PCL_PHASER_REQUIRE_DATA("pcl/bun4.pcd");
  const auto bun0 = loadXYZ("pcl/bun0.pcd");
  const auto target = loadXYZ("pcl/bun4.pcd");
  const Eigen::Matrix4d reference =
      fromRows({0.8806, 0.0365, -0.4724, 0.0345, -0.0235, 0.9992, 0.0333, -0.0015,
                0.4732, -0.0182, 0.8808, 0.0412});
  Eigen::Matrix4d move = Eigen::Matrix4d::Identity();
  move.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
  move(0, 3) = 100.0;
  auto source = pcl::make_shared<CloudXYZ>();
  pcl::transformPointCloud(*bun0, *source, move);
  const Eigen::Matrix4d truth = reference * move.inverse();

  bool converged = false;
  const Eigen::Matrix4d G = alignAboutCentroids(source, target, converged);
  std::printf("  global: RRE %.3f deg, mean displacement %.4f m\n", rreDeg(G, truth),
              meanDisplacement(*source, G, truth));
  ASSERT_TRUE(converged);
  EXPECT_LT(rreDeg(G, truth), 15.0); // SAC-IA itself lands 11-15 deg off here
  EXPECT_LT(meanDisplacement(*source, G, truth), 0.03);

  pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
  icp.setInputSource(source);
  icp.setInputTarget(target);
  icp.setMaxCorrespondenceDistance(0.05);
  icp.setMaximumIterations(50);
  icp.setTransformationEpsilon(1e-8);
  CloudXYZ out;
  icp.align(out, G.cast<float>());
  const Eigen::Matrix4d I = icp.getFinalTransformation().cast<double>();
  std::printf("  ICP: RRE %.4f deg, mean displacement %.5f m\n", rreDeg(I, truth),
              meanDisplacement(*source, I, truth));
  EXPECT_LT(rreDeg(I, truth), 0.2);
  EXPECT_LT(meanDisplacement(*source, I, truth), 0.003);
}

TEST(RealScans, SecondRotationHypothesisRescuesAMirrorPeak)
{
  // Pose 10 of the KITTI random-pose run (seed 2), range only (PointXYZ): the best
  // SO(3) peak of the first search is a ~168 degree mirror of the truth. With one
  // hypothesis the registration starts from it and fails (12-177 deg off: the
  // re-projection passes move it, how far depends on the grids they steer on); with
  // three, verification picks the right one. (The orientation histograms, on by
  // default, also rescue it; they are off here to test the range hypotheses.)
  const std::string relative = "lidar/kitti_raw_hdl64/0000000000.bin";
  PCL_PHASER_REQUIRE_DATA(relative);
  const CloudXYZ::Ptr scan = loadXYZ(relative);
  std::mt19937 rng(2);
  Eigen::Matrix4d T;
  for (int k = 0; k <= 10; ++k)
    T = randomPose(rng, 2.0);
  auto source = pcl::make_shared<CloudXYZ>();
  pcl::transformPointCloud(*scan, *source, Eigen::Matrix4d(T.inverse()));
  double error[2];
  for (int k = 0; k < 2; ++k) {
    pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> phaser;
    phaser.setNumberOfThreads(2);
    pcl::phaser::PhaserParameters params = phaser.getParameters();
    params.orientation_candidates = 0;
    params.rotation_candidates = k == 0 ? 1 : 3;
    phaser.setParameters(params);
    phaser.setInputSource(source);
    phaser.setInputTarget(scan);
    CloudXYZ aligned;
    phaser.align(aligned);
    error[k] = rreDeg(phaser.getFinalTransformation().cast<double>(), T);
    if (k == 1) {
      const pcl::phaser::PhaserResult& r = phaser.getResult();
      const std::vector<pcl::phaser::Hypothesis>& hypotheses = r.diagnostics.hypotheses;
      ASSERT_GE(hypotheses.size(), 2u);
      ASSERT_GE(r.chosen_hypothesis, 0);
      ASSERT_LT(r.chosen_hypothesis, static_cast<int>(hypotheses.size()));
      // Hypotheses are in the caller's frames: the estimate was refined from the
      // chosen one, whose residual rotation the later passes search within 20 deg
      // (kResidualTilt). (Another hypothesis may be nearer: when none meets the
      // limits, each rotation also tries further translation peaks, which are
      // polished on their own.)
      const Eigen::Matrix4d final_T = phaser.getFinalTransformation().cast<double>();
      const double chosen_angle =
          rreDeg(hypotheses[r.chosen_hypothesis].transformation, final_T);
      for (std::size_t h = 0; h < hypotheses.size(); ++h)
        std::printf("  hypothesis %zu: %.2f deg from the estimate\n", h,
                    rreDeg(hypotheses[h].transformation, final_T));
      EXPECT_LT(chosen_angle, 20.0);
    }
  }
  std::printf("  one hypothesis: RRE %.2f deg; three: RRE %.3f deg\n", error[0],
              error[1]);
  EXPECT_GT(error[0], 5.0);
  EXPECT_LT(error[1], 2.0);
}

TEST(RealScans, HalfViewFindsItsRotationAmongTheSpareOrientationPeaks)
{
  // Pose 4 of the 50 % overlap sweep on the HDL-32 scan: the half
  // of the scan about azimuth 97.3 deg, seen from a pose 1.8 m away. None of the 13
  // pass-1 rotations is within 15 deg of the truth: the range peaks are lost to the
  // half view, and the ten orientation peaks are the scene's 90, 120 and 180 deg
  // symmetric orientations. The pass-1 choice misses the limits, so the spare
  // orientation peaks become hypotheses too; one of them is right, and it wins.
  const std::string relative = "lidar/hdl32_fastgicp/251370668.pcd";
  PCL_PHASER_REQUIRE_DATA(relative);
  pcl::PhaserRegistration<PointT, PointT> phaser;
  const Eigen::Matrix4d T =
      alignSectorSeenFrom(load(relative), 1.698374324, 0.5 * M_PI,
                          {-0.1924567753, -0.3211896341, 0.927252721, 0.9903253856,
                           -0.9585730067, -0.1406753061, -0.2476857869, -1.171964386,
                           0.2099956676, -0.9365082366, -0.2808097975, -0.9449486051},
                          phaser);
  expectRightAndConverged(phaser, T);
  const pcl::phaser::PhaserResult& r = phaser.getResult();
  const pcl::phaser::PhaserParameters& p = phaser.getParameters();
  // The spare peaks follow the pass-1 hypotheses (ten of them), before the further
  // translation peaks of the pass-1 rotations.
  const int first_spare = p.rotation_candidates + p.orientation_candidates;
  EXPECT_GE(r.chosen_hypothesis, first_spare);
  EXPECT_LT(r.chosen_hypothesis, first_spare + 10);
}

TEST(RealScans, NarrowViewPolishReachesFromACoarseTranslationPeak)
{
  // Pose 2 of the 10 % overlap sweep on the KITTI scan: a 36 deg
  // sector about azimuth 40.7 deg, mostly road, seen from a pose 1.6 m away. An
  // orientation peak 2.8 deg from the truth gets a coarse translation peak 1-2 m off
  // (the coarse voxel is 2.4 m). From there a polish against the verification radius
  // alone matched little but the road and climbed to 7.4 deg / 2.1 m, and a 16 deg /
  // 3.6 m pose won and converged. The polish's first step against the coarse-voxel
  // index brings that hypothesis to the truth, and it wins.
  const std::string relative = "lidar/kitti_raw_hdl64/0000000000.bin";
  PCL_PHASER_REQUIRE_DATA(relative);
  pcl::PhaserRegistration<PointT, PointT> phaser;
  const Eigen::Matrix4d T =
      alignSectorSeenFrom(load(relative), 0.709854195, 0.1 * M_PI,
                          {-0.07082444269, -0.8698063192, 0.4882835911, 1.030241581,
                           -0.340663372, -0.4389886067, -0.8314069222, -0.9793265379,
                           0.9375139281, -0.2252242665, -0.2652200302, -0.4649522409},
                          phaser);
  expectRightAndConverged(phaser, T);
}

namespace {

/** NEES of the 6-D error (omega = Log(R_true R_est^T), nu = t_true - t_est) under
 *  getCovariance(), and of its translation part under the translation block. */
void nees(const Eigen::Matrix<double, 6, 6>& cov, const Eigen::Matrix4d& estimate,
          const Eigen::Matrix4d& truth, double& full, double& translation)
{
  Eigen::Matrix<double, 6, 1> e;
  const Eigen::AngleAxisd omega(Eigen::Matrix3d(
      truth.topLeftCorner<3, 3>() * estimate.topLeftCorner<3, 3>().transpose()));
  e.head<3>() = omega.angle() * omega.axis();
  e.tail<3>() = truth.topRightCorner<3, 1>() - estimate.topRightCorner<3, 1>();
  full = e.dot(cov.ldlt().solve(e));
  const Eigen::Vector3d nu = e.tail<3>();
  translation = nu.dot(cov.bottomRightCorner<3, 3>().ldlt().solve(nu));
}

} // namespace

TEST(RealScans, CovarianceConsistentOnKitti)
{
  // Issue 5's protocol on a few poses (seed 11, not the benchmark's): the KITTI scan at
  // PSNR 50 dB seen from random large poses. When converged the covariance is SPD, most
  // errors lie inside its 95 % ellipsoid, and the translation block is neither the old
  // block width (NEES ~0.02) nor overconfident.
  const std::string relative = "lidar/kitti_raw_hdl64/0000000000.bin";
  PCL_PHASER_REQUIRE_DATA(relative);
  const Cloud::Ptr scan = load(relative);
  pcl::phaser::bench::Condition noise;
  ASSERT_TRUE(pcl::phaser::bench::parseCondition("noise:50", noise));
  std::mt19937 rng(11);
  int converged = 0, inside = 0;
  double sum_full = 0.0, sum_translation = 0.0;
  for (int k = 0; k < 16; ++k) {
    pcl::PhaserRegistration<PointT, PointT> phaser;
    const Eigen::Matrix4d T = alignPerturbed(scan, noise, rng, phaser);
    if (!phaser.hasConverged())
      continue;
    ++converged;
    const Eigen::Matrix<double, 6, 6> cov = phaser.getCovariance();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(cov);
    EXPECT_LT((cov - cov.transpose()).norm(), 1e-12 * cov.norm()) << "pose " << k;
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0) << "pose " << k;
    double full = 0.0, translation = 0.0;
    nees(cov, phaser.getFinalTransformation().cast<double>(), T, full, translation);
    std::printf("  pose %2d: NEES %6.2f (translation %6.2f)\n", k, full, translation);
    sum_full += full;
    sum_translation += translation;
    inside += full <= 12.5916; // chi-square, 6 dof, 95 %
  }
  ASSERT_GE(converged, 12);
  EXPECT_GE(inside, 0.7 * converged);
  EXPECT_LT(sum_full / converged, 15.0);
  // The covariance of the final pose's own fit: mean 6-D NEES 2.8, mean
  // translation NEES 1.3 here (the spectral covariance before it gave 0.27 for the
  // translation), well above the old block width's 0.02.
  EXPECT_GT(sum_translation / converged, 0.1);
  EXPECT_LT(sum_translation / converged, 12.0);
}
