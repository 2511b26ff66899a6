/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Translation stage: grid sizing and voxelization (reference-implementation-notes.md
 * section 4 and the bugs listed there).
 */
#include "spatial/grid_frame.h"
#include "spatial_test_support.h"
#include "support/error.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <thread>

using namespace pcl::phaser;
using namespace pcl::phaser::test;

// ---------------------------------------------------------------------------------------
TEST(SpatialGrid, NextFftFriendlySize)
{
  const int cases[][2] = {{-3, 1},    {1, 1},     {7, 8},       {11, 12},    {97, 100},
                          {121, 125}, {127, 128}, {1000, 1000}, {1021, 1024}};
  for (const auto& c : cases)
    EXPECT_EQ(nextFftFriendlySize(c[0]), c[1]) << c[0];
}

TEST(SpatialGrid, SizedToTargetNotToAFixedBox)
{
  const Eigen::Matrix3Xd points = sceneBox(2000, 1);
  const Eigen::Vector3d lo = points.rowwise().minCoeff(),
                        hi = points.rowwise().maxCoeff();
  SpatialGridParameters params;
  params.grid_size = 100;
  const SpatialGrid grid = makeSpatialGrid(points, params);

  EXPECT_EQ(grid.dims.x(), 100); // longest axis, already 2^2 5^2
  EXPECT_LT(grid.dims.y(), grid.dims.x());
  EXPECT_LT(grid.dims.z(), grid.dims.y()); // flat scan -> flat grid
  for (int a = 0; a < 3; ++a)
    EXPECT_EQ(nextFftFriendlySize(grid.dims[a]), grid.dims[a]);
  // padding 0.5 doubles the extent of the longest axis plus one splat voxel per side.
  EXPECT_NEAR(grid.voxel_size, 2.0 * (hi.x() - lo.x()) / 98.0, 1e-12);
  for (int a = 0; a < 3; ++a) {
    const double e = hi[a] - lo[a];
    EXPECT_LE(grid.origin[a], lo[a] - 0.5 * e - grid.voxel_size + 1e-9);
    EXPECT_GE(grid.origin[a] + grid.extent()[a],
              hi[a] + 0.5 * e + grid.voxel_size - 1e-9);
    EXPECT_NEAR(grid.origin[a] + 0.5 * grid.extent()[a], 0.5 * (lo[a] + hi[a]), 1e-9);
  }
}

TEST(SpatialGrid, ExplicitVoxelSizeAndMinimumMargin)
{
  Eigen::Matrix3Xd plane = sceneBox(500, 2);
  plane.row(2).setZero(); // a perfectly flat target
  SpatialGridParameters params;
  params.voxel_size = 0.5;
  params.padding = 0.25;
  params.min_margin = 3.0;
  const SpatialGrid grid = makeSpatialGrid(plane, params);
  EXPECT_EQ(grid.voxel_size, 0.5);
  // z: 0 extent + 2 * 3 m margin = 12 voxels + 2 splat voxels = 14 -> 15.
  EXPECT_EQ(grid.dims.z(), 15);
  // x: ~40 m + 2 * max(10, 3) m = ~60 m = ~120 voxels + 2 -> 125.
  EXPECT_EQ(grid.dims.x(), 125);
  const Eigen::Array3d u =
      (Eigen::Vector3d(0.0, 0.0, 2.9) - grid.origin) / grid.voxel_size;
  EXPECT_TRUE((u >= 0.0).all() && (u < grid.dims.cast<double>().array()).all());
}

TEST(SpatialGrid, BadParametersThrow)
{
  const Eigen::Matrix3Xd points = sceneBox(100, 3);
  const auto with = [](auto change) {
    SpatialGridParameters p;
    change(p);
    return p;
  };
  for (int n : {-1, 0, 7, 1025, 4096})
    EXPECT_THROW(makeSpatialGrid(points, with([&](auto& p) { p.grid_size = n; })),
                 InvalidArgument)
        << n;
  EXPECT_NO_THROW(makeSpatialGrid(points, with([](auto& p) { p.grid_size = 8; })));
  EXPECT_NO_THROW(makeSpatialGrid(points, with([](auto& p) { p.grid_size = 1024; })));
  EXPECT_THROW(makeSpatialGrid(points, with([](auto& p) { p.voxel_size = -0.1; })),
               InvalidArgument);
  EXPECT_THROW(makeSpatialGrid(points, with([](auto& p) { p.voxel_size = NAN; })),
               InvalidArgument);
  EXPECT_THROW(makeSpatialGrid(points, with([](auto& p) { p.voxel_size = 1e-3; })),
               InvalidArgument); // would need > 1024 voxels per axis
  EXPECT_THROW(makeSpatialGrid(points, with([](auto& p) { p.padding = -0.5; })),
               InvalidArgument);
  EXPECT_THROW(makeSpatialGrid(points, with([](auto& p) { p.min_margin = INFINITY; })),
               InvalidArgument);
  // No finite points, or a single location with no way to derive a voxel size.
  EXPECT_THROW(makeSpatialGrid(Eigen::Matrix3Xd(3, 0)), InvalidArgument);
  EXPECT_THROW(makeSpatialGrid(Eigen::Matrix3Xd::Constant(3, 4, NAN)), InvalidArgument);
  EXPECT_THROW(makeSpatialGrid(Eigen::Matrix3Xd::Ones(3, 4)), InvalidArgument);
  EXPECT_NO_THROW(makeSpatialGrid(Eigen::Matrix3Xd::Ones(3, 4),
                                  with([](auto& p) { p.voxel_size = 1; })));
}

namespace {
/** Center of voxel \a index in meters. */
Eigen::Vector3d voxelCenter(const SpatialGrid& grid, const Eigen::Vector3i& index)
{
  return grid.origin + (index.cast<double>().array() + 0.5).matrix() * grid.voxel_size;
}
} // namespace

// ---------------------------------------------------------------------------------------
TEST(SpatialVoxelize, TrilinearSplatKeepsMassAndCentroid)
{
  SpatialGrid grid;
  grid.dims = Eigen::Vector3i(8, 9, 10);
  grid.voxel_size = 0.25;
  grid.origin = Eigen::Vector3d(-1.0, 2.0, 0.5);
  const Eigen::Vector3d p(-0.3, 3.07, 1.61);
  SpatialVoxelParameters linear;
  linear.saturation = 0.0;
  const SpatialVolume v = voxelize(grid, Eigen::Matrix3Xd(p), linear);
  double mass = 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  int nonzero = 0;
  for (std::size_t i = 0; i < v.values.size(); ++i) {
    mass += v.values[i];
    centroid += v.values[i] * voxelCenter(grid, grid.voxelIndex(i));
    nonzero += v.values[i] != 0.0;
  }
  EXPECT_NEAR(mass, 1.0, 1e-12);
  EXPECT_LT((centroid / mass - p).norm(), 1e-12);
  EXPECT_EQ(nonzero, 8);

  // A point on a voxel center with the default saturation W0 = 1: value 1 - exp(-1).
  const Eigen::Vector3d c = voxelCenter(grid, Eigen::Vector3i(3, 4, 5));
  const SpatialVolume s = voxelize(grid, Eigen::Matrix3Xd(c));
  EXPECT_NEAR(s.values[grid.flatIndex(3, 4, 5)], 1.0 - std::exp(-1.0), 1e-12);
}

TEST(SpatialVoxelize, OutsidePointsAreDroppedNotAliased)
{
  SpatialGrid grid;
  grid.dims = Eigen::Vector3i(10, 12, 8);
  grid.voxel_size = 1.0;
  // Every point is more than one voxel outside on at least one axis.
  std::vector<Eigen::Vector3d> outside = {
      {-1.6, 3.5, 2.5}, {3.5, -1.6, 2.5}, {3.5, 3.5, -1.6}, {11.6, 3.5, 2.5},
      {3.5, 13.6, 2.5}, {3.5, 3.5, 9.6},  {-5.0, -5.0, -5}, {-1.5, 11.5, 7.5},
      {1e30, 3.5, 2.5}, {-1e30, 0, 0},    {12.0, 12.0, 12}, {-1.0001, 5.5, 5.5},
      {INFINITY, 1, 1}};
  Eigen::Matrix3Xd points(3, static_cast<Eigen::Index>(outside.size()));
  for (std::size_t i = 0; i < outside.size(); ++i)
    points.col(static_cast<Eigen::Index>(i)) = outside[i];
  const SpatialVolume v = voxelize(grid, points);
  for (double x : v.values)
    ASSERT_EQ(x, 0.0);

  // A quarter voxel outside each face: only the quarter weight towards the border layer
  // lands, and only in that layer (wrapping would put the rest on the opposite face).
  SpatialVoxelParameters linear;
  linear.saturation = 0.0;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      Eigen::Vector3d p(4.5, 5.5, 3.5);
      p[axis] = side ? grid.dims[axis] + 0.25 : -0.25;
      const SpatialVolume h = voxelize(grid, Eigen::Matrix3Xd(p), linear);
      double total = 0.0;
      for (std::size_t i = 0; i < h.values.size(); ++i) {
        total += h.values[i];
        if (h.values[i] != 0.0) {
          EXPECT_EQ(grid.voxelIndex(i)[axis], side ? grid.dims[axis] - 1 : 0);
        }
      }
      EXPECT_NEAR(total, 0.25, 1e-12) << axis << " " << side;
    }
}

TEST(SpatialVoxelize, BitIdenticalForAnyThreadCount)
{
  // Many points per voxel (a dense 2 m cube inside the scene), so any change of the
  // summation order with the thread count would change the rounding.
  Eigen::Matrix3Xd points(3, 40000);
  points << sceneBox(20000, 4), randomBox(20000, Eigen::Vector3d(1.0, 1.0, 1.0), 5);
  const SpatialGrid grid = makeSpatialGrid(points);
  const SpatialVolume a = voxelize(grid, points);
  for (int threads : {2, 3, 4}) {
    SpatialVoxelParameters p;
    p.num_threads = threads;
    for (int repeat = 0; repeat < 2; ++repeat)
      EXPECT_TRUE(bitIdentical(a.values, voxelize(grid, points, p).values));
  }

  // The whole translation search too.
  const Eigen::Matrix3Xd source = points.colwise() - Eigen::Vector3d(1.3, -0.7, 0.2);
  const SpatialSpectrum t = computeSpectrum(a);
  SpatialVoxelParameters two;
  two.num_threads = 2;
  const SpatialSpectrum s = computeSpectrum(voxelize(grid, source, two));
  const SpatialVolume c1 = correlateSpectra(t, s, 1);
  EXPECT_TRUE(bitIdentical(c1.values, correlateSpectra(t, s, 2).values));
  const SpatialCorrelationResult r1 =
      findSpatialPeak(c1, SpatialPeakRefinement::kGaussian, 1);
  const SpatialCorrelationResult r2 =
      findSpatialPeak(c1, SpatialPeakRefinement::kGaussian, 2);
  EXPECT_EQ(r1.index, r2.index);
  EXPECT_EQ(r1.shift, r2.shift);
  EXPECT_EQ(r1.peak_value, r2.peak_value);
  EXPECT_EQ(r1.score, r2.score);
}

TEST(SpatialVoxelize, BadArgumentsThrow)
{
  SpatialGrid grid;
  grid.dims = Eigen::Vector3i(8, 8, 8);
  const Eigen::Matrix3Xd points = Eigen::Matrix3Xd::Ones(3, 5);
  SpatialVoxelParameters p;
  p.saturation = -1.0;
  EXPECT_THROW(voxelize(grid, points, p), InvalidArgument);
  p.saturation = 1.0;
  p.num_threads = -1;
  EXPECT_THROW(voxelize(grid, points, p), InvalidArgument);
  SpatialGrid bad = grid;
  bad.dims.y() = 0;
  EXPECT_THROW(voxelize(bad, points), InvalidArgument);
  bad = grid;
  bad.voxel_size = 0.0;
  EXPECT_THROW(voxelize(bad, points), InvalidArgument);
}

// A 40 x 10 m strip turned 30 deg about z: the grid frame turns it back (to 0.05 deg,
// up to the quarter turns that give the same box) and keeps z.
TEST(GridFrame, TurnsAStripOntoTheGridAxes)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  Eigen::Matrix3Xd strip(3, 5000);
  for (Eigen::Index i = 0; i < strip.cols(); ++i)
    strip.col(i) << 40.0 * u(rng), 10.0 * u(rng), 3.0 * u(rng);
  const double turn = 30.0 * M_PI / 180.0;
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()).matrix();
  const Eigen::Matrix3d A = detail::gridAlignedYaw(Q * strip);
  const Eigen::Matrix3d D = A * Q; // a quarter turn about z, or none
  EXPECT_NEAR(D(2, 2), 1.0, 1e-12);
  const double residual =
      std::fmod(std::atan2(D(1, 0), D(0, 0)) + 2.0 * M_PI, M_PI / 2);
  EXPECT_LT(std::min(residual, M_PI / 2 - residual) * 180.0 / M_PI, 0.05);
  // Already aligned, a disc (no yaw shrinks its box by 1 %), too few points: none.
  EXPECT_TRUE(detail::gridAlignedYaw(strip).isIdentity(0.0));
  Eigen::Matrix3Xd disc(3, 3600);
  for (Eigen::Index i = 0; i < disc.cols(); ++i)
    disc.col(i) << std::cos(i * M_PI / 1800), std::sin(i * M_PI / 1800), 0.0;
  EXPECT_TRUE(detail::gridAlignedYaw(disc).isIdentity(0.0));
  EXPECT_TRUE(detail::gridAlignedYaw(strip.leftCols(2)).isIdentity(0.0));
}
