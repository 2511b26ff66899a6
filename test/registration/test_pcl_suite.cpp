/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * PCL's own registration tests (PointCloudLibrary/pcl test/registration/: test_sac_ia,
 * test_fpcs_ia, test_kfpcs_ia) with their set-ups and pass criteria, the aligner
 * replaced by a default-constructed pcl::PhaserRegistration and nothing else changed:
 * the drop-in promise, checked. The bunny cases also require hasConverged(), which
 * PCL's aligners set whatever they found.
 */
#include "test_data.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>
#include <pcl/io/pcd_io.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

template <typename PointT>
typename pcl::PointCloud<PointT>::Ptr load(const std::string& relative)
{
  auto cloud = pcl::make_shared<pcl::PointCloud<PointT>>();
  if (pcl::io::loadPCDFile(pcl::phaser::test::dataPath(relative), *cloud) < 0)
    ADD_FAILURE() << "cannot read " << relative;
  return cloud;
}

/** The source of test_sac_ia / test_fpcs_ia: bun0 moved by \a offset and 90 deg about z
 *  (transformPointCloud with a translation and a quaternion, as PCL's tests call it).
 */
pcl::PointCloud<pcl::PointXYZ>::Ptr movedBun0(const Eigen::Vector3f& offset)
{
  const auto bun0 = load<pcl::PointXYZ>("pcl/bun0.pcd");
  const float angle = static_cast<float>(M_PI) / 2.0f;
  const Eigen::Quaternionf rotation(std::cos(angle / 2), 0, 0, std::sin(angle / 2));
  auto moved = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::transformPointCloud(*bun0, *moved, offset, rotation);
  return moved;
}

/** Share of \a source points within \a distance of \a target after \a T: PCL's
 *  SampleConsensusPrerejective::getInliers() criterion. */
double inlierFraction(const pcl::PointCloud<pcl::PointXYZ>& source,
                      const pcl::PointCloud<pcl::PointXYZ>::Ptr& target,
                      const Eigen::Matrix4f& T, float distance)
{
  pcl::PointCloud<pcl::PointXYZ> moved;
  pcl::transformPointCloud(source, moved, T);
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(target);
  std::vector<int> index(1);
  std::vector<float> squared(1);
  std::size_t inliers = 0;
  for (const pcl::PointXYZ& p : moved.points)
    inliers += tree.nearestKSearch(p, 1, index, squared) == 1 &&
               squared[0] < distance * distance;
  return static_cast<double>(inliers) / static_cast<double>(source.size());
}

/** \a reg (default-constructed) aligned as PCL's tests align: the whole source out. */
template <typename PointT>
void alignAsPcl(pcl::PhaserRegistration<PointT, PointT>& reg,
                const typename pcl::PointCloud<PointT>::Ptr& source,
                const typename pcl::PointCloud<PointT>::Ptr& target)
{
  reg.setInputSource(source);
  reg.setInputTarget(target);
  pcl::PointCloud<PointT> registered;
  reg.align(registered);
  EXPECT_EQ(registered.size(), source->size());
}

} // namespace

// test_sac_ia.cpp, TEST(PCL, SampleConsensusInitialAlignment): bun0 moved 100 m along x
// and yawed 90 deg, aligned to bun4; fitness (mean squared NN distance) < 0.0005 m^2,
// again under PCL's four search-tree caching schemes.
TEST(PclSuite, SampleConsensusInitialAlignment)
{
  PCL_PHASER_REQUIRE_DATA("pcl/bun0.pcd");
  PCL_PHASER_REQUIRE_DATA("pcl/bun4.pcd");
  const auto source = movedBun0(Eigen::Vector3f(100, 0, 0));
  const auto target = load<pcl::PointXYZ>("pcl/bun4.pcd");
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> reg;
  alignAsPcl<pcl::PointXYZ>(reg, source, target);
  EXPECT_LT(reg.getFitnessScore(), 0.0005);
  EXPECT_TRUE(reg.hasConverged()) << reg.getResult().error;
  std::printf("  sac_ia: fitness %.6f m^2\n", reg.getFitnessScore());
  pcl::PointCloud<pcl::PointXYZ> registered;
  for (int iter = 0; iter < 4; ++iter) {
    const bool force_cache = iter / 2 != 0, force_cache_reciprocal = iter % 2 != 0;
    auto tree = pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
    if (force_cache)
      tree->setInputCloud(target);
    reg.setSearchMethodTarget(tree, force_cache);
    auto tree_reciprocal = pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
    if (force_cache_reciprocal)
      tree_reciprocal->setInputCloud(source);
    reg.setSearchMethodSource(tree_reciprocal, force_cache_reciprocal);
    reg.align(registered);
    EXPECT_EQ(registered.size(), source->size());
    EXPECT_LT(reg.getFitnessScore(), 0.0005) << "caching scheme " << iter;
    EXPECT_TRUE(reg.hasConverged()) << "caching scheme " << iter;
  }
}

// test_sac_ia.cpp, TEST(PCL, SampleConsensusPrerejective): the same set-up; more than
// 95 % of the source points within 0.1 m (its MaxCorrespondenceDistance) of the target.
TEST(PclSuite, SampleConsensusPrerejective)
{
  PCL_PHASER_REQUIRE_DATA("pcl/bun0.pcd");
  PCL_PHASER_REQUIRE_DATA("pcl/bun4.pcd");
  const auto source = movedBun0(Eigen::Vector3f(100, 0, 0));
  const auto target = load<pcl::PointXYZ>("pcl/bun4.pcd");
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> reg;
  alignAsPcl<pcl::PointXYZ>(reg, source, target);
  const double inliers =
      inlierFraction(*source, target, reg.getFinalTransformation(), 0.1f);
  std::printf("  prerejective: inlier fraction %.4f\n", inliers);
  EXPECT_GT(inliers, 0.95);
  EXPECT_TRUE(reg.hasConverged()) << reg.getResult().error;
}

// test_fpcs_ia.cpp, TEST(PCL, FPCSInitialAlignment): bun0 moved 1 m along x and yawed
// 90 deg; every element of the 4x4 within 0.45 of FPCS's answer (test_fpcs_ia_data.h).
TEST(PclSuite, FpcsInitialAlignment)
{
  PCL_PHASER_REQUIRE_DATA("pcl/bun0.pcd");
  PCL_PHASER_REQUIRE_DATA("pcl/bun4.pcd");
  const auto source = movedBun0(Eigen::Vector3f(1, 0, 0));
  const auto target = load<pcl::PointXYZ>("pcl/bun4.pcd");
  pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> reg;
  alignAsPcl<pcl::PointXYZ>(reg, source, target);
  Eigen::Matrix4f fpcs;
  fpcs << -0.0019f, 0.8266f, -0.5628f, -0.0378f, -0.9999f, -0.0094f, -0.0104f, 0.9997f,
      -0.0139f, 0.5627f, 0.8265f, 0.0521f, 0.f, 0.f, 0.f, 1.f;
  const float worst = (reg.getFinalTransformation() - fpcs).cwiseAbs().maxCoeff();
  std::printf("  fpcs_ia: worst element %.4f\n", worst);
  EXPECT_LT(worst, 0.45f);
  EXPECT_TRUE(reg.hasConverged()) << reg.getResult().error;
}

// test_kfpcs_ia.cpp, TEST(PCL, KFPCSInitialAlignment): keypoints of two office scans
// (PointXYZI); the rest transform final^-1 * truth within 0.1745 rad and 1 m.
TEST(PclSuite, KfpcsInitialAlignment)
{
  PCL_PHASER_REQUIRE_DATA("pcl/office1_keypoints.pcd");
  PCL_PHASER_REQUIRE_DATA("pcl/office2_keypoints.pcd");
  const auto source = load<pcl::PointXYZI>("pcl/office1_keypoints.pcd");
  const auto target = load<pcl::PointXYZI>("pcl/office2_keypoints.pcd");
  pcl::PhaserRegistration<pcl::PointXYZI, pcl::PointXYZI> reg;
  alignAsPcl<pcl::PointXYZI>(reg, source, target);
  Eigen::Matrix4f truth;
  truth << -0.6946f, -0.7194f, -0.0051f, -3.6352f, 0.7194f, -0.6945f, -0.0100f,
      -2.3865f, 0.0037f, -0.0106f, 0.9999f, 0.7778f, 0.f, 0.f, 0.f, 1.f;
  const Eigen::Matrix4f rest =
      reg.getFinalTransformation().colPivHouseholderQr().solve(truth);
  const float angle = Eigen::AngleAxisf(rest.topLeftCorner<3, 3>()).angle();
  const float translation = rest.topRightCorner<3, 1>().norm();
  std::printf("  kfpcs_ia: %.4f rad, %.4f m, converged %d\n", angle, translation,
              static_cast<int>(reg.hasConverged()));
  EXPECT_LT(angle, 0.1745f);
  EXPECT_LT(translation, 1.f);
  // Not required to converge: 1.1-1.3k keypoints over a 26 m office are seen from the
  // scans' origins but are too sparse for the surface normals verification needs
  // (measured: inliers 0.14, constraint 0), so hasConverged() honestly says false.
}
