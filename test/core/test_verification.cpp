/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "channels/surface_orientation.h"
#include "index/point_index.h"
#include "point_test_support.h"
#include "spatial/spatial_correlation.h"
#include "support/error.h"
#include "verification/verification.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

using namespace pcl::phaser;

namespace {

using test::randomPoints;

/** A wall x = d (|y|, |z| < half) sampled on a grid of step h. */
Eigen::Matrix3Xd wall(double d, double half, double h)
{
  const int k = static_cast<int>(2 * half / h) + 1;
  Eigen::Matrix3Xd p(3, k * k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      p.col(i * k + j) = Eigen::Vector3d(d, -half + i * h, -half + j * h);
  return p;
}

/** Checks PointIndex(points, radius) against brute force at every query; returns how
 *  many queries have a point within the radius. */
int expectNearestAsBruteForce(const Eigen::Matrix3Xd& points,
                              const Eigen::Matrix3Xd& queries, double radius)
{
  const PointIndex index(points, radius);
  int found = 0;
  for (Eigen::Index q = 0; q < queries.cols(); ++q) {
    const double brute =
        (points.colwise() - queries.col(q)).colwise().squaredNorm().minCoeff();
    const double got =
        index.nearestSquaredDistance(queries.col(q), Eigen::Vector3d::Zero(), 0.0);
    if (brute <= radius * radius) {
      EXPECT_NEAR(got, brute, 1e-12);
      ++found;
    } else {
      EXPECT_TRUE(std::isinf(got));
    }
  }
  return found;
}

} // namespace

TEST(PointIndex, NearestDistanceMatchesBruteForceWithinTheRadius)
{
  const Eigen::Matrix3Xd points = randomPoints(2000, 5.0, 1);
  const Eigen::Matrix3Xd queries = randomPoints(300, 5.5, 2);
  const double radius = 0.7;
  const int found = expectNearestAsBruteForce(points, queries, radius);
  EXPECT_GT(found, 50); // the test exercised both branches
  EXPECT_LT(found, 300);
}

TEST(PointIndex, NearestWithNormalsMatchesBruteForce)
{
  // Dense points, so most queries find their match in their own cell and skip
  // neighbor cells: the skipped cells must never hold a nearer agreeing point.
  const Eigen::Matrix3Xd points = randomPoints(6000, 3.0, 3);
  Eigen::Matrix3Xd normals = randomPoints(6000, 1.0, 4);
  normals.colwise().normalize();
  const Eigen::Matrix3Xd queries = randomPoints(400, 3.2, 5);
  const double radius = 0.5;
  const PointIndex index(points, radius, normals);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  int found = 0;
  for (Eigen::Index q = 0; q < queries.cols(); ++q) {
    double brute = radius * radius;
    Eigen::Index expected = -1;
    for (Eigen::Index k = 0; k < points.cols(); ++k) {
      const double d2 = (points.col(k) - queries.col(q)).squaredNorm();
      if (normals.col(k).dot(up) >= kMinNormalCosine && d2 <= brute) {
        brute = d2;
        expected = k;
      }
    }
    const Eigen::Index got = index.nearest(queries.col(q), up, kMinNormalCosine);
    ASSERT_EQ(got < 0, expected < 0);
    if (got >= 0) {
      EXPECT_EQ(index.point(got), points.col(expected));
      ++found;
    }
  }
  EXPECT_GT(found, 100);
  EXPECT_LT(found, 400);
}

TEST(PointIndex, ClustersFarApartOnEveryAxisMatchBruteForce)
{
  // Clusters hundreds of meters apart on each axis, negative coordinates included:
  // their cell keys differ in the high bits of every axis field, and the queries, half
  // near a cluster and half between them, probe occupied and empty slots of the cell
  // table (their box is far too sparse for the index's directory, which the other
  // tests' compact clouds use).
  const Eigen::Matrix3Xd unit = randomPoints(3000, 1.0, 6);
  const Eigen::Matrix3Xd noise = randomPoints(400, 1.5, 7);
  Eigen::Matrix3Xd points(3, unit.cols()), queries(3, noise.cols());
  const auto center = [](Eigen::Index i) {
    return Eigen::Vector3d(-900.0 + 300.0 * (i % 7), 250.0 * ((i / 7) % 3) - 250.0,
                           -400.0 * ((i / 21) % 2));
  };
  for (Eigen::Index i = 0; i < unit.cols(); ++i)
    points.col(i) = center(i % 42) + unit.col(i);
  for (Eigen::Index q = 0; q < noise.cols(); ++q)
    queries.col(q) =
        center(q % 42) + noise.col(q) +
        (q % 2 ? Eigen::Vector3d(150.0, 0.0, 0.0) : Eigen::Vector3d::Zero());
  const double radius = 0.3;
  const int found = expectNearestAsBruteForce(points, queries, radius);
  EXPECT_GT(found, 20);  // near-cluster queries that find a point ...
  EXPECT_LT(found, 200); // ... and between-cluster ones that do not
}

TEST(PointIndex, EmptyAndNonFiniteQueriesFindNothing)
{
  const PointIndex empty(Eigen::Matrix3Xd(3, 0), 1.0);
  EXPECT_TRUE(std::isinf(empty.nearestSquaredDistance(Eigen::Vector3d::Zero(),
                                                      Eigen::Vector3d::Zero(), 0.0)));
  const PointIndex one(Eigen::Matrix3Xd::Zero(3, 1), 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isinf(one.nearestSquaredDistance(Eigen::Vector3d(nan, 0, 0),
                                                    Eigen::Vector3d::Zero(), 0.0)));
  EXPECT_THROW(groupByVoxel(Eigen::Matrix3Xd::Zero(3, 1), 0.0), InvalidArgument);
}

TEST(VoxelCentroids, OneSamplePerOccupiedVoxelInKeyOrder)
{
  Eigen::Matrix3Xd p(3, 4);
  p << 0.1, 0.3, 2.5, 0.2, 0.1, 0.1, 0.5, 0.2, 0.1, 0.1, 0.5, 0.2;
  const Eigen::Matrix3Xd c = voxelCentroids(p, 1.0);
  ASSERT_EQ(c.cols(), 2);
  EXPECT_TRUE(c.col(0).isApprox(Eigen::Vector3d(0.2, 0.4 / 3, 0.4 / 3)));
  EXPECT_TRUE(c.col(1).isApprox(Eigen::Vector3d(2.5, 0.5, 0.5)));
  EXPECT_EQ(voxelCentroids(p, 1.0, 2).cols(), 1);
}

TEST(GroupByVoxel, GroupsInKeyOrderAsASortOfThePairs)
{
  // Clouds of several extents (one voxel to 2e5 voxels per axis, negative coordinates
  // included): groups in increasing key, each holding its points in index order, as
  // std::sort of the (key, index) pairs gives.
  std::mt19937 rng(11);
  for (const double extent : {0.5, 30.0, 4000.0, 2e5}) {
    std::uniform_real_distribution<double> u(-extent, 0.3 * extent);
    Eigen::Matrix3Xd p(3, 3000);
    for (Eigen::Index i = 0; i < p.cols(); ++i)
      p.col(i) = Eigen::Vector3d(u(rng), u(rng), 0.01 * u(rng));
    p.col(7) = p.col(3); // equal keys keep their index order
    std::vector<std::pair<std::int64_t, Eigen::Index>> reference;
    for (Eigen::Index i = 0; i < p.cols(); ++i) {
      std::int64_t key = 0;
      ASSERT_TRUE(voxelKey(p.col(i), 1.0, key));
      reference.emplace_back(key, i);
    }
    std::sort(reference.begin(), reference.end());
    const VoxelGroups g = groupByVoxel(p, 1.0);
    ASSERT_EQ(g.order.size(), reference.size());
    for (std::size_t k = 0; k < reference.size(); ++k)
      ASSERT_EQ(g.order[k], reference[k].second) << "extent " << extent;
    for (std::size_t k = 0; k < g.size(); ++k) {
      ASSERT_EQ(g.keys[k], reference[g.offsets[k]].first);
      ASSERT_EQ(g.keys[k], reference[g.offsets[k + 1] - 1].first);
    }
  }
}

TEST(VerifyPose, RightPoseVerifiesAndAShiftedOneDoesNot)
{
  const Eigen::Matrix3Xd target = randomPoints(5000, 10.0, 3);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(1.0, -2.0, 0.5);
  // source = R^T (target - t): the pose (R, t) maps it back exactly.
  const Eigen::Matrix3Xd source = R.transpose() * (target.colwise() - t);
  const PointIndex index(target, 0.3);
  const auto unweighted = [](const Eigen::Matrix3Xd& points) {
    return VerificationSamples{points, Eigen::VectorXd::Ones(points.cols()), {}};
  };
  const Verification right = verifyPose(index, unweighted(source), R, t);
  EXPECT_DOUBLE_EQ(right.inlier_fraction, 1.0);
  EXPECT_NEAR(right.score, 1.0, 1e-9);
  const Verification wrong =
      verifyPose(index, unweighted(source), R, t + Eigen::Vector3d(30, 0, 0));
  EXPECT_EQ(wrong.inlier_fraction, 0.0);
  EXPECT_EQ(wrong.score, 0.0);
  const Verification none = verifyPose(index, unweighted(Eigen::Matrix3Xd(3, 0)), R, t);
  EXPECT_EQ(none.inlier_fraction, 0.0);
  EXPECT_THROW(verifyPose(index, {source, Eigen::VectorXd::Ones(3), {}}, R, t),
               InvalidArgument);
}

TEST(VerifyPose, SameResultForAnyThreadCount)
{
  const Eigen::Matrix3Xd target = randomPoints(4000, 10.0, 4);
  const Eigen::Matrix3Xd source = randomPoints(3000, 10.0, 5);
  const PointIndex index(target, 0.5);
  const FreeSpace seen = freeSpace(target, 32, 0.5);
  const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(source.cols(), 1.0, 2.0);
  const VerificationSamples samples{source, w, {}};
  const Verification one = verifyPose(index, samples, Eigen::Matrix3d::Identity(),
                                      Eigen::Vector3d::Zero(), 1, &seen);
  for (int threads : {2, 3, 8}) {
    const Verification many = verifyPose(index, samples, Eigen::Matrix3d::Identity(),
                                         Eigen::Vector3d::Zero(), threads, &seen);
    EXPECT_EQ(one.inlier_fraction, many.inlier_fraction);
    EXPECT_EQ(one.score, many.score);
    EXPECT_EQ(one.free_space_violation, many.free_space_violation);
  }
}

TEST(FreeSpace, SamplesInFrontOfWhatTheSensorSawViolateAndThoseBehindDoNot)
{
  const Eigen::Matrix3Xd target = wall(10.0, 4.0, 0.1); // seen from the origin
  const FreeSpace seen = freeSpace(target, 64, 0.5);
  const PointIndex index(target, 0.3);
  const Eigen::Matrix3Xd samples = wall(1.0, 0.3, 0.05); // same directions, at ~1/10
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const VerificationSamples s{samples, Eigen::VectorXd::Ones(samples.cols()), {}};
  const Verification in_front =
      verifyPose(index, s, I, Eigen::Vector3d(4.0, 0, 0), 1, &seen);
  EXPECT_GT(in_front.free_space_violation, 0.99); // at x = 5 m, the sensor saw to 10 m
  const Verification behind =
      verifyPose(index, s, I, Eigen::Vector3d(14.0, 0, 0), 1, &seen);
  EXPECT_EQ(behind.free_space_violation, 0.0); // occluded by the wall: unknown, no vote
  const Verification on_it =
      verifyPose(index, s, I, Eigen::Vector3d(9.0, 0, 0), 1, &seen);
  EXPECT_EQ(on_it.free_space_violation, 0.0); // within the margin of the wall
  EXPECT_EQ(on_it.inlier_fraction, 1.0);
}

// The per-sample terms are what the verification sums: the weighted mean of the
// closeness is the score, the weighted share of violations the free-space violation.
TEST(VerifyPose, PerSampleTermsSumToTheVerification)
{
  const Eigen::Matrix3Xd target = wall(10.0, 4.0, 0.1);
  const FreeSpace seen = freeSpace(target, 64, 0.5);
  const PointIndex index(target, 0.3);
  // Half the samples on the wall, half 5 m in front of it (in space the sensor saw
  // through, with no target point near).
  const Eigen::Matrix3Xd on = wall(9.95, 1.0, 0.25), in_front = wall(5.0, 1.0, 0.25);
  const int n = static_cast<int>(on.cols());
  Eigen::Matrix3Xd samples(3, 2 * n);
  samples << on, in_front;
  const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(samples.cols(), 1.0, 3.0);
  const VerificationSamples s{samples, w, {}};
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d t = Eigen::Vector3d::Zero();
  const std::vector<double> closeness = sampleCloseness(index, s, I, t);
  const std::vector<double> violations = sampleViolations(seen, samples, I, t);
  ASSERT_EQ(closeness.size(), 2u * n);
  ASSERT_EQ(violations.size(), 2u * n);
  double score = 0.0, violating = 0.0;
  for (int i = 0; i < 2 * n; ++i) {
    EXPECT_EQ(closeness[i] > 0.0, i < n) << i;
    EXPECT_EQ(violations[i], i < n ? 0.0 : 1.0) << i;
    score += w[i] * closeness[i];
    violating += w[i] * violations[i];
  }
  const Verification v = verifyPose(index, s, I, t, 1, &seen);
  EXPECT_NEAR(v.score, score / w.sum(), 1e-12);
  EXPECT_NEAR(v.free_space_violation, violating / w.sum(), 1e-12);
  EXPECT_NEAR(v.inlier_fraction, w.head(n).sum() / w.sum(), 1e-12);
  for (int threads : {2, 8})
    EXPECT_EQ(sampleCloseness(index, s, I, t, threads), closeness);
  EXPECT_EQ(sampleViolations(FreeSpace{}, samples, I, t),
            std::vector<double>(2u * n, 0.0)); // nothing seen: no violation
}

TEST(VerifyPose, OnlyTargetPointsWithAgreeingNormalsMatch)
{
  const Eigen::Matrix3Xd target = wall(5.0, 2.0, 0.1);
  const Eigen::Matrix3Xd normals =
      Eigen::Vector3d(-1, 0, 0).replicate(1, target.cols()); // faces the origin
  const PointIndex index(target, 0.3, normals);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::VectorXd w = Eigen::VectorXd::Ones(target.cols());
  const VerificationSamples same{target, w, normals};
  EXPECT_EQ(verifyPose(index, same, I, Eigen::Vector3d::Zero()).inlier_fraction, 1.0);
  const VerificationSamples flipped{target, w, -normals}; // seen from the other side
  EXPECT_EQ(verifyPose(index, flipped, I, Eigen::Vector3d::Zero()).inlier_fraction,
            0.0);
  const VerificationSamples unknown{target, w,
                                    Eigen::Matrix3Xd::Zero(3, target.cols())};
  EXPECT_EQ(verifyPose(index, unknown, I, Eigen::Vector3d::Zero()).inlier_fraction,
            1.0);
  EXPECT_THROW(PointIndex(target, 0.3, Eigen::Matrix3Xd::Zero(3, 2)), InvalidArgument);
}

TEST(SurfacePatches, APlaneGivesItsNormalTowardsTheViewpoint)
{
  const Eigen::Matrix3Xd p = wall(5.0, 1.95, 0.1); // 10 x 10 points per voxel
  const SurfacePatches patches = surfacePatches(p, 1.0, Eigen::Vector3d::Zero());
  ASSERT_GT(patches.normals.cols(), 10);
  for (Eigen::Index i = 0; i < patches.normals.cols(); ++i) {
    EXPECT_NEAR(patches.normals(0, i), -1.0, 1e-9); // faces the origin
    EXPECT_GT(patches.weights[i], 0.9);
  }
  const SurfacePatches other_side = surfacePatches(p, 1.0, Eigen::Vector3d(10, 0, 0));
  EXPECT_NEAR(other_side.normals(0, 0), 1.0, 1e-9);
}

TEST(OrientationWeights, BalanceAPlaneThatHoldsMostSamples)
{
  // A floor of 1600 samples and a wall of 400: each class weighs 1 / count (floored at
  // 2 % of the samples), so both carry the same total weight.
  Eigen::Matrix3Xd floor(3, 1600), side(3, 400);
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      floor.col(i * 40 + j) = Eigen::Vector3d(0.5 * i + 0.25, 0.5 * j + 0.25, 0.01);
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 10; ++j)
      side.col(i * 10 + j) = Eigen::Vector3d(0.01, 0.5 * i + 0.25, 0.5 * j + 0.25);
  Eigen::Matrix3Xd all(3, 2000);
  all << floor, side;
  const SurfacePatches patches = surfacePatches(all, 1.0, Eigen::Vector3d(5, 5, 5), 3);
  const Eigen::VectorXd w = orientationWeights(patches, all);
  EXPECT_NEAR(w.sum(), 1.0, 1e-12);
  EXPECT_NEAR(w.head(1600).sum(), w.tail(400).sum(), 0.1);
}

TEST(CorrelateSpectraWhitened, ZeroExponentIsThePlainCorrelationAndAShiftIsFound)
{
  const Eigen::Matrix3Xd target = randomPoints(3000, 8.0, 6);
  const Eigen::Vector3d shift(1.5, -0.75, 0.5);
  const Eigen::Matrix3Xd source = target.colwise() - shift;
  SpatialGridParameters gp;
  gp.grid_size = 64;
  const SpatialGrid grid = makeSpatialGrid(target, gp);
  const SpatialSpectrum T = computeSpectrum(voxelize(grid, target));
  const SpatialSpectrum S = computeSpectrum(voxelize(grid, source));
  const SpatialVolume plain = correlateSpectra(T, S);
  const SpatialVolume zero = correlateSpectraWhitened(T, SpatialSpectrum(S), 0.0);
  ASSERT_EQ(plain.values.size(), zero.values.size());
  for (std::size_t i = 0; i < plain.values.size(); i += 97)
    EXPECT_NEAR(plain.values[i], zero.values[i],
                1e-9 * std::abs(plain.values[0]) + 1e-9);
  for (double exponent : {0.5, 1.0}) {
    const SpatialCorrelationResult r =
        findSpatialPeak(correlateSpectraWhitened(T, SpatialSpectrum(S), exponent));
    EXPECT_LT((r.shift - shift).norm(), 0.5 * grid.voxel_size) << exponent;
  }
  EXPECT_THROW(correlateSpectraWhitened(T, SpatialSpectrum(S), 1.5), InvalidArgument);
  EXPECT_THROW(correlateSpectraWhitened(T, SpatialSpectrum(S), -0.1), InvalidArgument);
}
