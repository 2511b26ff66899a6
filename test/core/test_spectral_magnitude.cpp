/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The occupancy magnitude on shells: unchanged by a shift, turned with the cloud, and
 * its SO(3) correlation peaks at the rotation between two clouds that share no center.
 */
#include "channels/spectral_magnitude.h"
#include "pipeline/cloud_spectra.h"
#include "so3_test_support.h"
#include "uncertainty/peak_neighborhood.h"

#include <gtest/gtest.h>

#include <random>

namespace {

using namespace pcl::phaser;

/** An irregular object: points on three boxes' faces of different sizes, 0.2 m. */
Eigen::Matrix3Xd object(int n, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector3d sizes[] = {
      {0.10, 0.06, 0.04}, {0.03, 0.08, 0.03}, {0.05, 0.02, 0.07}};
  const Eigen::Vector3d offsets[] = {{0, 0, 0}, {0.06, 0.05, 0.0}, {-0.04, 0.0, 0.05}};
  Eigen::Matrix3Xd p(3, n);
  for (int i = 0; i < n; ++i) {
    const int box = i % 3;
    Eigen::Vector3d q(u(rng), u(rng), u(rng));
    const int axis = static_cast<int>((u(rng) + 1.0) * 1.5) % 3;
    q[axis] = q[axis] < 0 ? -1.0 : 1.0;
    p.col(i) = offsets[box] + sizes[box].cwiseProduct(q);
  }
  return p;
}

MagnitudeShells shellsOf(const Eigen::Matrix3Xd& points, double voxel)
{
  SpatialGridParameters grid;
  grid.voxel_size = voxel;
  return magnitudeShells(
      detail::occupancySpectrum(makeSpatialGrid(points, grid), points, 1), 32);
}

TEST(SpectralMagnitude, ShiftedCloudCorrelatesAtTheRotation)
{
  const Eigen::Matrix3Xd source = object(30000, 1);
  std::mt19937 rng(5);
  const Eigen::Matrix3d R = test::randomRotation(rng);
  // Moved by a shift that is not a whole voxel: no common center, and the grids differ.
  const Eigen::Matrix3Xd target =
      (R * source).colwise() + Eigen::Vector3d(0.31, -0.7, 2.1);
  const double voxel = 0.003;
  const MagnitudeShells f = shellsOf(target, voxel), h = shellsOf(source, voxel);
  ASSERT_EQ(f.shells.size(), h.shells.size());
  const So3CorrelationGrid C = correlateShells(f, h, 2);
  const So3GridIndex peak = C.argmax(2);
  const Eigen::Matrix3d found = rotationFromEuler(gridEuler(peak, C.outputBandwidth()));
  EXPECT_LT(rotationDistance(found, R) * 180.0 / M_PI, 6.0); // a cell is 5.6 deg
  EXPECT_GT(C(peak) / (f.norm * h.norm), 0.8);
}

TEST(SpectralMagnitude, RefusesMismatchedShells)
{
  MagnitudeShells a = shellsOf(object(3000, 2), 0.004), b;
  EXPECT_THROW(correlateShells(a, b), InvalidArgument);
  EXPECT_THROW(magnitudeShells(SpatialSpectrum(), 32), InvalidArgument);
}

TEST(So3CorrelationGridSum, AccumulateAddsSampleBySample)
{
  std::mt19937 rng(3);
  const SphericalSpectrum F = test::randomSpectrum(8, rng),
                          H = test::randomSpectrum(8, rng);
  const auto correlator = So3Correlator::instance(8);
  So3CorrelationGrid sum = correlator->correlate(F, H);
  const So3CorrelationGrid one = correlator->correlate(F, H);
  sum.accumulate(one);
  for (int j = 0; j < sum.size(); j += 3)
    for (int a = 0; a < sum.size(); a += 5)
      EXPECT_NEAR(sum(j, a, 2), 2.0 * one(j, a, 2), 1e-12);
  EXPECT_THROW(sum.accumulate(So3Correlator::instance(4)->correlate(
                   test::randomSpectrum(4, rng), test::randomSpectrum(4, rng))),
               InvalidArgument);
}

} // namespace
