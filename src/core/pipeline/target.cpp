/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * A Target and what the engine derives from its points once: the cues of its center
 * and the last model.
 */
#include "pipeline/projection_center.h"
#include "pipeline/target.h"
#include "spatial/grid_frame.h"

#include <mutex>

namespace pcl::phaser {

/** What a Target derives from its points: looksSensorCentered and the last model. */
struct Target::Cache {
  std::mutex mutex;
  int sensor_centered = -1; ///< looksSensorCentered about the origin; < 0: not computed
  int origin_on_data = -1;  ///< originOnData about the origin; < 0: not computed
  int seen_from_origin = -1; ///< hiddenShare about the origin small; < 0: not computed
  std::shared_ptr<const detail::TargetModel> model;
  ProjectionCenter center = ProjectionCenter::SensorOrigin; ///< of model
  Eigen::Vector3d offset = Eigen::Vector3d::Zero(); ///< the projection center of model
  /** The axes of model: its points are axes (p - offset). */
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  std::optional<detail::SearchRegion> region; ///< model is of the points in it only
};

Target::Target(Eigen::Matrix3Xd points, ChannelValues channels)
    : points_(std::move(points))
    , channels_(std::move(channels))
    , cache_(std::make_unique<Cache>())
{
}

Target::~Target() = default;

const ChannelValues& TargetAccess::channels(const Target& t)
{
  return t.channels_;
}

Target::Cache& TargetAccess::cache(const Target& t)
{
  return *t.cache_;
}

namespace detail {
namespace {

/** Whether the target's frame origin lies on its data (its cache locked). */
bool targetOriginOnData(const Target& target)
{
  auto& cache = TargetAccess::cache(target);
  if (cache.origin_on_data < 0)
    cache.origin_on_data =
        originOnData(target.points(), Eigen::Vector3d::Zero()) ? 1 : 0;
  return cache.origin_on_data == 1;
}

/** Whether the target is seen from its frame origin (hiddenShare, cached); a map
 *  (with a region, or far from its origin) counts as seen. */
bool targetSeenFromOrigin(const Target& target, bool map_target)
{
  auto& cache = TargetAccess::cache(target);
  std::lock_guard<std::mutex> lock(cache.mutex);
  if (map_target || !targetOriginOnData(target))
    return true;
  if (cache.seen_from_origin < 0)
    cache.seen_from_origin =
        hiddenShare(target.points(), Eigen::Vector3d::Zero()) <= kMaxHiddenShare;
  return cache.seen_from_origin == 1;
}

} // namespace

ProjectionCenter chooseCenter(const Target& target, const Eigen::Matrix3Xd& moved,
                              const Eigen::Matrix4d& guess, ProjectionCenter requested)
{
  if (requested != ProjectionCenter::Automatic)
    return requested;
  auto& cache = TargetAccess::cache(target);
  bool target_lidar = false;
  {
    std::lock_guard<std::mutex> lock(cache.mutex);
    if (cache.sensor_centered < 0)
      cache.sensor_centered =
          looksSensorCentered(target.points(), Eigen::Vector3d::Zero()) ? 1 : 0;
    target_lidar = cache.sensor_centered == 1 || !targetOriginOnData(target);
  }
  return target_lidar && looksSensorCentered(moved, guess.topRightCorner<3, 1>())
             ? ProjectionCenter::SensorOrigin
             : ProjectionCenter::Centroid;
}

StageMode stageMode(const Target& target, const Eigen::Matrix3Xd& moved,
                    const Eigen::Matrix4d& guess, ProjectionCenter center,
                    bool map_target)
{
  StageMode mode;
  mode.sensor_centered = center == ProjectionCenter::SensorOrigin;
  // Each free-space test needs its cloud seen from its center (an object's frame origin
  // is no scanner's; a scan moved by the guess is seen from the guess's translation).
  mode.viewpoints = mode.sensor_centered && targetSeenFromOrigin(target, map_target);
  mode.source_viewpoint =
      mode.viewpoints &&
      hiddenShare(moved, guess.topRightCorner<3, 1>()) <= kMaxHiddenShare;
  return mode;
}

std::shared_ptr<const TargetModel>
targetModel(const Target& target, ProjectionCenter center,
            const StageSettings& settings, const std::optional<SearchRegion>& region,
            Eigen::Vector3d& offset, Eigen::Matrix3d& axes, double& target_ms)
{
  auto& cache = TargetAccess::cache(target);
  std::lock_guard<std::mutex> lock(cache.mutex);
  if (!cache.model || cache.center != center || cache.region != region ||
      !sameModel(cache.model->settings, settings)) {
    cache.model.reset();
    if (region) {
      const RegionCloud cloud = thinForModel(
          cropToRegion(target.points(), TargetAccess::channels(target), *region),
          settings.params.spatial_grid_size, settings.params.voxel_size);
      cache.offset = region->center;
      cache.model = prepareTarget(cloud.points, settings, cloud.channels);
    } else {
      Eigen::Matrix3Xd points = target.points();
      // About a far origin the target would be a small cap of the sphere, and the true
      // shift would lie outside its translation grid.
      const bool site_frame = !targetOriginOnData(target);
      cache.offset = center == ProjectionCenter::Centroid || site_frame
                         ? Eigen::Vector3d(points.rowwise().mean())
                         : Eigen::Vector3d::Zero();
      points.colwise() -= cache.offset;
      cache.axes = site_frame ? gridAlignedYaw(points) : Eigen::Matrix3d::Identity();
      if (site_frame)
        points = cache.axes * points;
      cache.model = prepareTarget(points, settings, TargetAccess::channels(target));
    }
    if (region)
      cache.axes = Eigen::Matrix3d::Identity();
    cache.center = center;
    cache.region = region;
    target_ms = cache.model->preparation_ms;
  }
  offset = cache.offset;
  axes = cache.axes;
  return cache.model;
}

} // namespace detail
} // namespace pcl::phaser
