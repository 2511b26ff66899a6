/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Bad input refused with a message in the user's words: coincident points at the
 * engine's entry with the cloud named, indices that select no point named as such.
 */
#include "registration_test_scene.h"

#include <pcl_phaser/phaser_registration.h>

#include <gtest/gtest.h>

#include <limits>
#include <string>

using namespace registration_test;

namespace {

using Phaser = pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ>;

/** \brief The error of one align() of \a source onto \a target. */
std::string alignError(Phaser& phaser, const CloudXYZ::Ptr& source,
                       const CloudXYZ::Ptr& target)
{
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  CloudXYZ out;
  phaser.align(out);
  EXPECT_FALSE(phaser.hasConverged());
  return phaser.getResult().error;
}

CloudXYZ::Ptr copies(const pcl::PointXYZ& p, std::size_t n)
{
  auto c = pcl::make_shared<CloudXYZ>();
  c->resize(n, p);
  return c;
}

} // namespace

TEST(InputMessages, CoincidentPointsAreRefusedAtTheEntryNamingTheCloud)
{
  const auto scene = makeScene<pcl::PointXYZ>();
  const auto point = copies(pcl::PointXYZ(1, 2, 3), 5);
  Phaser a, b, c;
  const std::string source_error = alignError(a, point, scene);
  EXPECT_EQ(source_error, "every finite point of the source cloud (5) is at one "
                          "position: registration needs points spread over a scene");
  const std::string target_error = alignError(b, scene, point);
  EXPECT_TRUE(has(target_error, "the target cloud (5) is at one position"))
      << target_error;
  EXPECT_TRUE(has(alignError(c, copies(pcl::PointXYZ(1, 2, 3), 1), scene),
                  "source cloud (1) is at one position"));
  for (const std::string& e : {source_error, target_error})
    EXPECT_FALSE(has(e, "makeSpatialGrid") || has(e, "min_margin")) << e;
}

TEST(InputMessages, IndicesThatSelectNoPointAreNamed)
{
  const auto scene = makeScene<pcl::PointXYZ>();
  auto source = pcl::make_shared<CloudXYZ>(*scene);
  (*source)[0].x = std::numeric_limits<float>::quiet_NaN();
  source->is_dense = false;
  Phaser phaser;
  phaser.setIndices(pcl::make_shared<pcl::Indices>());
  EXPECT_EQ(alignError(phaser, source, scene),
            "the indices given to setIndices (0) select no finite source point; pass "
            "indices of finite points, or none to use the whole cloud");
  Phaser nan_only;
  nan_only.setIndices(pcl::make_shared<pcl::Indices>(pcl::Indices{0}));
  EXPECT_TRUE(has(alignError(nan_only, source, scene),
                  "the indices given to setIndices (1) select no"));
  // Without indices an all-NaN cloud is the cloud's fault.
  auto nan_cloud = copies(pcl::PointXYZ(0, 0, 0), 3);
  for (auto& q : *nan_cloud)
    q.x = std::numeric_limits<float>::quiet_NaN();
  nan_cloud->is_dense = false;
  Phaser plain;
  EXPECT_EQ(alignError(plain, nan_cloud, scene),
            "the source cloud has no finite points");
}
