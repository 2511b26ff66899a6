/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The gravity prior (PhaserParameters::max_tilt_deg) on the simulated demo pairs (up to
 * 3 deg of relative roll and pitch): within the prior they are found as without it; a
 * source tilted 30 deg more is outside it, so no result tilted beyond the prior is
 * returned and none converges.
 */
#include "scan_simulator.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace {

constexpr double kDeg = M_PI / 180.0;
using Cloud = pcl::PointCloud<pcl::PointXYZI>;

struct Outcome {
  double rre = 0.0, rte = 0.0, tilt = 0.0; ///< deg, m, deg
  bool converged = false;
};

/** \a source registered onto \a target with the prior \a max_tilt_deg (0: off), against
 *  the truth \a T. */
Outcome run(const Cloud& source, const Cloud& target, const Eigen::Matrix4d& T,
            double max_tilt_deg)
{
  pcl::PhaserRegistration<pcl::PointXYZI, pcl::PointXYZI> phaser;
  pcl::phaser::PhaserParameters params = phaser.getParameters();
  params.num_threads = 2;
  params.max_tilt_deg = max_tilt_deg;
  phaser.setParameters(params);
  phaser.setInputSource(pcl::make_shared<Cloud>(source));
  phaser.setInputTarget(pcl::make_shared<Cloud>(target));
  Cloud out;
  phaser.align(out);
  const Eigen::Matrix4d G = phaser.getFinalTransformation().cast<double>();
  Outcome o;
  o.rre =
      Eigen::AngleAxisd(G.topLeftCorner<3, 3>() * T.topLeftCorner<3, 3>().transpose())
          .angle() /
      kDeg;
  o.rte = (G.topRightCorner<3, 1>() - T.topRightCorner<3, 1>()).norm();
  o.tilt = std::acos(std::min(1.0, G(2, 2))) / kDeg;
  o.converged = phaser.hasConverged();
  std::printf("  max_tilt %.0f: RRE %.2f deg RTE %.2f m, tilt %.2f deg, converged %d\n",
              max_tilt_deg, o.rre, o.rte, o.tilt, o.converged ? 1 : 0);
  return o;
}

TEST(TiltPrior, DemoPairFoundWithinThePrior)
{
  const pcl::phaser::ScanPair pair = pcl::phaser::makeDemoPair(1);
  const Outcome o = run(pair.source, pair.target, pair.T_target_source, 10.0);
  EXPECT_TRUE(o.converged);
  EXPECT_LT(o.rre, 1.0);
  EXPECT_LT(o.rte, 0.2);
}

TEST(TiltPrior, ThirtyDegreeTiltIsNotFound)
{
  const pcl::phaser::ScanPair pair = pcl::phaser::makeDemoPair(1);
  // The source rolled 30 deg about its x axis: T' = T Rx(30)^-1 maps it.
  Eigen::Matrix4d roll = Eigen::Matrix4d::Identity();
  roll.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(30.0 * kDeg, Eigen::Vector3d::UnitX()).toRotationMatrix();
  Cloud rolled;
  pcl::transformPointCloud(pair.source, rolled, roll);
  const Eigen::Matrix4d T = pair.T_target_source * roll.inverse();
  const double true_tilt = std::acos(T(2, 2)) / kDeg;
  ASSERT_GT(true_tilt, 25.0);
  // Without the prior the pose is found: the case is solvable.
  const Outcome full = run(rolled, pair.target, T, 0.0);
  EXPECT_TRUE(full.converged);
  EXPECT_LT(full.rre, 2.0);
  // With it: never a result tilted beyond it (half a cell at B = 64 for the drift of
  // the refinements), and not converged.
  const Outcome prior = run(rolled, pair.target, T, 10.0);
  EXPECT_LE(prior.tilt, 10.0 + 90.0 / 64.0);
  EXPECT_FALSE(prior.converged);
}

} // namespace
