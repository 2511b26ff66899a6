/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The position prior in the search: which target points a sensor in the region could
 * see and which translations the search may take.
 */
#include "index/point_index.h"
#include "priors/region.h"
#include "support/error.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace pcl::phaser::detail {
namespace {

/** Sensor ranges are rounded up to this, so nearby queries share a cached target. */
constexpr double kRangeStep = 10.0;
/** The sensor range is estimated from at most this many points. */
constexpr Eigen::Index kRangeSamples = 20000;
/** Fewer target points in the region: nothing to register against. */
constexpr Eigen::Index kMinRegionPoints = 100;
/** The finest cell the target model uses, in coarse voxels: its indexes keep one
 *  point per cube of half a coarse voxel / 8 (target_model.cpp), so a map thinned to it
 *  loses nothing a stage sees. */
constexpr double kFinestCell = 1.0 / 16.0;

/** The 99th-percentile distance of \a points from \a sensor, rounded up. */
double sensorRange(const Eigen::Matrix3Xd& points, const Eigen::Vector3d& sensor)
{
  const Eigen::Index step = std::max<Eigen::Index>(1, points.cols() / kRangeSamples);
  std::vector<double> r;
  for (Eigen::Index i = 0; i < points.cols(); i += step)
    r.push_back((points.col(i) - sensor).norm());
  const std::size_t k = (r.size() * 99) / 100;
  std::nth_element(r.begin(), r.begin() + k, r.end());
  return kRangeStep * std::ceil(r[k] / kRangeStep);
}

} // namespace

SearchRegion searchRegion(const Region& region, const Eigen::Matrix3Xd& moved,
                          const Eigen::Vector3d& sensor)
{
  SearchRegion out;
  out.center = {region.x, region.y, region.z};
  out.radius = region.radius;
  const double range =
      region.sensor_range > 0.0 ? region.sensor_range : sensorRange(moved, sensor);
  out.reach = region.radius + range;
  return out;
}

RegionCloud cropToRegion(const Eigen::Matrix3Xd& points, const ChannelValues& channels,
                         const SearchRegion& region)
{
  const double reach2 = region.reach * region.reach;
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    if ((points.col(i) - region.center).squaredNorm() <= reach2)
      keep.push_back(i);
  if (static_cast<Eigen::Index>(keep.size()) < kMinRegionPoints)
    throw InvalidArgument("the target has " + std::to_string(keep.size()) +
                          " points within " + std::to_string(region.reach) +
                          " m of the region's center (region_radius + sensor_range); "
                          "check the region against the target's frame");
  RegionCloud cloud;
  cloud.points.resize(3, static_cast<Eigen::Index>(keep.size()));
  for (std::size_t k = 0; k < keep.size(); ++k)
    cloud.points.col(k) = points.col(keep[k]) - region.center;
  for (const Eigen::VectorXd& values : channels) {
    Eigen::VectorXd kept(static_cast<Eigen::Index>(keep.size()));
    for (std::size_t k = 0; k < keep.size(); ++k)
      kept(k) = values(keep[k]);
    cloud.channels.push_back(std::move(kept));
  }
  return cloud;
}

RegionCloud thinForModel(const RegionCloud& cloud, int grid_size, double voxel_size)
{
  SpatialGridParameters grid;
  grid.grid_size = grid_size;
  grid.voxel_size = voxel_size;
  const double cell = kFinestCell * makeSpatialGrid(cloud.points, grid).voxel_size;
  const VoxelGroups groups = groupByVoxel(cloud.points, cell);
  RegionCloud out;
  const auto n = static_cast<Eigen::Index>(groups.size());
  out.points.resize(3, n);
  out.channels.assign(cloud.channels.size(), Eigen::VectorXd(n));
  for (Eigen::Index g = 0; g < n; ++g) {
    const Eigen::Index begin = groups.offsets[g], end = groups.offsets[g + 1];
    const double count = static_cast<double>(end - begin);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (Eigen::Index k = begin; k < end; ++k)
      sum += cloud.points.col(groups.order[k]);
    out.points.col(g) = sum / count;
    for (std::size_t c = 0; c < cloud.channels.size(); ++c) {
      double value = 0.0;
      for (Eigen::Index k = begin; k < end; ++k)
        value += cloud.channels[c](groups.order[k]);
      out.channels[c](g) = value / count;
    }
  }
  return out;
}

namespace {

template <typename Volume>
void keepShifts(Volume& correlation, const Eigen::Vector3d& center, double radius)
{
  const SpatialGrid& grid = correlation.grid;
  if (correlation.values.empty())
    return;
  const auto lowest =
      *std::min_element(correlation.values.begin(), correlation.values.end());
  const auto lag = [&](int i, int n) { return 2 * i < n ? i : i - n; };
  const double radius2 = radius * radius;
  for (int ix = 0; ix < grid.dims.x(); ++ix)
    for (int iy = 0; iy < grid.dims.y(); ++iy)
      for (int iz = 0; iz < grid.dims.z(); ++iz) {
        const Eigen::Vector3d shift =
            Eigen::Vector3d(lag(ix, grid.dims.x()), lag(iy, grid.dims.y()),
                            lag(iz, grid.dims.z())) *
            grid.voxel_size;
        if ((shift - center).squaredNorm() > radius2)
          correlation.values[grid.flatIndex(ix, iy, iz)] = lowest;
      }
}

} // namespace

void keepShiftsWithin(SpatialVolume& correlation, const Eigen::Vector3d& center,
                      double radius)
{
  keepShifts(correlation, center, radius);
}

void keepShiftsWithin(SpatialVolumeF& correlation, const Eigen::Vector3d& center,
                      double radius)
{
  keepShifts(correlation, center, radius);
}

} // namespace pcl::phaser::detail
