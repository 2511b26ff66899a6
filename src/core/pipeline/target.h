/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Internal to the engine: what align() asks of a Target, each answer derived from its
// points once and cached (target.cpp).
#include "pipeline/stage_settings.h"
#include "pipeline/target_model.h"
#include "priors/region.h"

#include <pcl_phaser/core/pipeline.h>

#include <Eigen/Core>

#include <memory>
#include <optional>

namespace pcl::phaser {

/** The engine's access to a Target's channels and cache. */
class TargetAccess {
public:
  static const ChannelValues& channels(const Target& t);
  static Target::Cache& cache(const Target& t);
};

namespace detail {

/** The projection center of a pair: \a requested unless Automatic; then the sensor
 *  origins when both clouds look sensor-centered (\a moved: the source with the
 *  \a guess, about its translation), else the centroids. A target whose origin is off
 *  its data (a map in a site frame) leaves the choice to the source. */
ProjectionCenter chooseCenter(const Target& target, const Eigen::Matrix3Xd& moved,
                              const Eigen::Matrix4d& guess, ProjectionCenter requested);

/** Which free-space tests apply to a pair about \a center; \a moved: the source with
 *  the \a guess; \a map_target: a region prior places the source in the target. */
StageMode stageMode(const Target& target, const Eigen::Matrix3Xd& moved,
                    const Eigen::Matrix4d& guess, ProjectionCenter center,
                    bool map_target);

/** The target model, cached or prepared (its time into \a target_ms), its center
 *  into \a offset and its axes into \a axes (its points are axes (p - offset)): with a
 *  \a region, of the points a sensor there could see, about the region's center; else
 *  the centroid about centroids or when the frame origin is off the data, else the
 *  origin. A target whose frame origin is off its data (a map in a site frame) is
 *  turned about z onto its smallest box (gridAlignedYaw). */
std::shared_ptr<const TargetModel>
targetModel(const Target& target, ProjectionCenter center,
            const StageSettings& settings, const std::optional<SearchRegion>& region,
            Eigen::Vector3d& offset, Eigen::Matrix3d& axes, double& target_ms);

} // namespace detail
} // namespace pcl::phaser
