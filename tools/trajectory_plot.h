/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * A top view (x, y) of trajectories and loop edges as a PNG, written with zlib only.
 */
#pragma once

#include <Eigen/Core>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace pcl {
namespace phaser {
namespace graph {

/** \brief A polyline in world x, y (meters) and its RGB color. */
struct Polyline {
  std::vector<Eigen::Vector2d> points;
  std::array<unsigned char, 3> color{0, 0, 0};
  bool connected = true; ///< false: segments between consecutive pairs of points
};

/** \brief Draw \a lines, in order, scaled to fit a \a size x \a size white image with
 *  equal axes, x to the right and y up, and write it as an 8-bit RGB PNG.
 *  \return the reason on failure, else empty */
std::string writeTopView(const std::string& path, const std::vector<Polyline>& lines,
                         int size = 800);

} // namespace graph
} // namespace phaser
} // namespace pcl
