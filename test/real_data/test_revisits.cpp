/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Revisits: two different scans of one place taken meters apart (balm_handheld), with
 * default parameters about the sensor origin. The reference poses are LiDAR-inertial
 * odometry, good to centimeters: success is judged at 5 deg / 0.6 m.
 */
#include "protocol.h"
#include "real_data_support.h"
#include "revisits.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/point_types.h>

#include <Eigen/Geometry>

#include <cmath>
#include <fstream>
#include <sstream>

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZI>;
const std::string kDir = "lidar/balm_handheld/";

/** T_target_source of the pair (source, target) in pairs.txt; identity if absent. */
Eigen::Matrix4d referencePose(const std::string& source, const std::string& target)
{
  std::ifstream in(pcl::phaser::test::dataPath(kDir + "pairs.txt"));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream is(line);
    std::string s, t;
    double dist, rot, overlap;
    if (line.empty() || line[0] == '#' || !(is >> s >> t >> dist >> rot >> overlap))
      continue;
    if (s != source || t != target)
      continue;
    Eigen::Matrix4d T;
    for (int i = 0; i < 16; ++i)
      is >> T(i / 4, i % 4);
    return T;
  }
  ADD_FAILURE() << "pair " << source << " " << target << " not in pairs.txt";
  return Eigen::Matrix4d::Identity();
}

/** T_target_source of scans fullS.pcd and fullT.pcd from their odometry poses (the
 *  derived pairs of the revisit study). */
Eigen::Matrix4d odometryPose(int source, int target)
{
  std::vector<pcl::phaser::bench::ScanPose> poses;
  std::string error;
  if (!pcl::phaser::bench::readScanPoses(
          pcl::phaser::test::dataPath(kDir + "poses_T_world_lidar.txt"), poses, error))
    ADD_FAILURE() << error;
  Eigen::Matrix4d world_source = Eigen::Matrix4d::Identity(),
                  world_target = world_source;
  for (const auto& pose : poses) {
    if (pose.index == source)
      world_source = pose.world_lidar;
    if (pose.index == target)
      world_target = pose.world_lidar;
  }
  return world_target.inverse() * world_source;
}

struct Errors {
  double rotation_deg, translation_m;
};

Errors errors(const Eigen::Matrix4d& estimate, const Eigen::Matrix4d& truth)
{
  const Eigen::Matrix3d dR =
      estimate.topLeftCorner<3, 3>().transpose() * truth.topLeftCorner<3, 3>();
  return {Eigen::AngleAxisd(dR).angle() * 180.0 / M_PI,
          (estimate.topRightCorner<3, 1>() - truth.topRightCorner<3, 1>()).norm()};
}

/** A balm_handheld scan, non-finite points removed. */
Cloud::Ptr scan(const std::string& name)
{
  return pcl::phaser::test::loadFiniteCloud<pcl::PointXYZI>(kDir + name);
}

/** The 90 deg azimuth sector of \a full about \a center_deg, as a sensor with a narrow
 *  field of view would see it. */
Cloud::Ptr quarterSector(const Cloud& full, double center_deg)
{
  auto sector = pcl::make_shared<Cloud>(full);
  pcl::phaser::bench::keepSector(*sector, center_deg * M_PI / 180.0, 0.25 * M_PI);
  return sector;
}

/** Registers with defaults; \a why gets the verification figures. */
Eigen::Matrix4d align(const Cloud::ConstPtr& source, const Cloud::ConstPtr& target,
                      bool& converged, std::string* why = nullptr)
{
  const pcl::phaser::PhaserResult result =
      pcl::phaser::test::alignWithDefaults<pcl::PointXYZI>(source, target);
  converged = result.converged;
  const pcl::phaser::PhaserDiagnostics& diagnostics = result.diagnostics;
  if (why)
    *why = "inlier fraction " +
           std::to_string(diagnostics.verification.inlier_fraction) +
           ", free-space violations " +
           std::to_string(diagnostics.verification.free_space_violation) + " / " +
           std::to_string(diagnostics.verification.reverse_free_space_violation) +
           ", rank " + std::to_string(diagnostics.verification.rank) + " (runner-up " +
           std::to_string(diagnostics.runner_up_rank) + ", difference error " +
           std::to_string(diagnostics.runner_up_error) + ")";
  return result.transformation.cast<float>().cast<double>();
}

/** \a source against \a target with defaults: within 5 deg / 0.6 m of \a truth, and
 *  converged. */
void expectRegistered(const std::string& source, const std::string& target,
                      const Eigen::Matrix4d& truth)
{
  bool converged = false;
  std::string why;
  const Errors e = errors(align(scan(source), scan(target), converged, &why), truth);
  why = source + " -> " + target + ": " + why;
  EXPECT_LT(e.rotation_deg, 5.0) << why;
  EXPECT_LT(e.translation_m, 0.6) << why;
  EXPECT_TRUE(converged) << why;
}

/** The 90 deg sector of \a source about \a center_deg against \a target: when it
 *  converges, the pose is right (5 deg / 2 m). */
void expectRightIfConverged(const std::string& source, double center_deg,
                            const std::string& target)
{
  bool converged = true;
  std::string why;
  const Errors e = errors(
      align(quarterSector(*scan(source), center_deg), scan(target), converged, &why),
      referencePose(source, target));
  if (converged) {
    EXPECT_LT(e.rotation_deg, 5.0) << why;
    EXPECT_LT(e.translation_m, 2.0) << why;
  }
}

} // namespace

// Pairs 3-20 m apart, chosen across the distance range before any tuning on them
// (the first pairs of each distance bin in pairs.txt).
TEST(Revisits, PairsMetersApartRegisterAndConverge)
{
  PCL_PHASER_REQUIRE_DATA(kDir + "pairs.txt");
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {"full18.pcd", "full36.pcd"},   // 3.2 m, 117 deg
      {"full90.pcd", "full108.pcd"},  // 8.3 m, 156 deg
      {"full84.pcd", "full162.pcd"},  // 12.4 m, 83 deg
      {"full54.pcd", "full156.pcd"}}; // 20.8 m, 92 deg
  for (const auto& [s, t] : pairs)
    expectRegistered(s, t, referencePose(s, t));
}

TEST(Revisits, SwappedInputsGiveTheInverse)
{
  PCL_PHASER_REQUIRE_DATA(kDir + "pairs.txt");
  const auto a = scan("full120.pcd");
  const auto b = scan("full132.pcd");
  const Eigen::Matrix4d truth = referencePose("full120.pcd", "full132.pcd");
  bool forward_converged = false, backward_converged = false;
  const Errors forward = errors(align(a, b, forward_converged), truth);
  const Errors backward = errors(align(b, a, backward_converged), truth.inverse());
  EXPECT_LT(forward.rotation_deg, 5.0);
  EXPECT_LT(forward.translation_m, 0.6);
  EXPECT_LT(backward.rotation_deg, 5.0);
  EXPECT_LT(backward.translation_m, 0.6);
  EXPECT_TRUE(forward_converged);
  EXPECT_TRUE(backward_converged);
}

// A scan against a scan of another place (KITTI, a road) does not converge, and
// neither does a revisit pair whose source is moved 40 m away so that nothing overlaps.
TEST(Revisits, UnrelatedPlacesDoNotConverge)
{
  PCL_PHASER_REQUIRE_DATA(kDir + "full18.pcd");
  PCL_PHASER_REQUIRE_DATA("lidar/kitti_raw_hdl64/0000000000.bin");
  const auto balm = scan("full18.pcd");
  const auto kitti = pcl::phaser::test::loadFiniteCloud<pcl::PointXYZI>(
      "lidar/kitti_raw_hdl64/0000000000.bin");
  bool converged = true;
  std::string why;
  align(balm, kitti, converged, &why);
  EXPECT_FALSE(converged) << why;
  align(kitti, balm, converged, &why);
  EXPECT_FALSE(converged) << why;
}

// A pair 18.5 m apart (full48 -> full90) whose scene has a 90 deg symmetry. The
// symmetric pose (90 deg off) puts its source samples on the target's surfaces, and
// only a few in space the target's sensor saw through, but many of the target's samples
// in space the source's sensor saw through. Ranked by the larger of the two shares, the
// polish left the right pose just over the reverse limit and the symmetric pose won
// pass 1, to be refused by hasConverged(); ranked by their sum, the right pose is
// polished within every limit and wins. Converged means right, and the pose is right.
TEST(Revisits, ConvergedMeansRightOnASymmetricScene)
{
  PCL_PHASER_REQUIRE_DATA(kDir + "full48.pcd");
  bool converged = true;
  std::string why;
  const Errors e =
      errors(align(scan("full48.pcd"), scan("full90.pcd"), converged, &why),
             referencePose("full48.pcd", "full90.pcd"));
  if (converged) {
    EXPECT_LT(e.rotation_deg, 5.0) << why;
    EXPECT_LT(e.translation_m, 2.0) << why;
  }
  EXPECT_LT(e.rotation_deg, 5.0) << why;
  EXPECT_LT(e.translation_m, 0.6) << why;
}

// A 90 deg sector of a scan, as a sensor with a narrow field of view would see it,
// against a full scan of the same yard 12 m away (full36 -> full108; the sector of
// the partial-revisit study). No pass-1 hypothesis is near the
// right pose, and the 180 deg mirror of the yard meets every verification limit;
// a pose that breaks a limit ranks higher, so the evidence does not single out the
// mirror, and hasConverged() must not claim it.
TEST(Revisits, NarrowViewOfASymmetricYardDoesNotClaimTheMirror)
{
  PCL_PHASER_REQUIRE_DATA(kDir + "full36.pcd");
  expectRightIfConverged("full36.pcd", 26.9, "full108.pcd");
}

// A 90 deg sector of full6 against full78, 13.5 m away (a sector of the partial-revisit
// study, --source-wedge 0.25). No pass-1 hypothesis is near the
// right pose; the 180 deg flip of the yard meets every verification limit and ranks
// above every other hypothesis, but by less than the choice of the sector's few hundred
// samples explains (runner_up_error), so hasConverged() must not claim it.
TEST(Revisits, NarrowViewFlipThatBarelyOutranksTheRunnerUpDoesNotConverge)
{
  PCL_PHASER_REQUIRE_DATA(kDir + "full6.pcd");
  expectRightIfConverged("full6.pcd", 175.8091, "full78.pcd");
}

// A derived pair 3.8 m apart (full102 -> full84). In pass 1 the right rotation's pose
// is 1.75 m off, before the final refinement: it has the most inliers (0.43) and the
// highest rank (0.29), but its constraint (0.025) is below the limit, while a 90 deg
// pose with half as many inliers (rank 0.01) lies just inside every limit. Ranked by
// the limits first, that pose won pass 1 and the pair failed;
// ranked by the evidence, the right pose wins and is refined to centimeters.
TEST(Revisits, PassOneRanksAnUnrefinedRightPoseByItsEvidenceNotByTheLimits)
{
  PCL_PHASER_REQUIRE_DATA(kDir + "poses_T_world_lidar.txt");
  expectRegistered("full102.pcd", "full84.pcd", odometryPose(102, 84));
}
