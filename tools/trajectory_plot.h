/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * A top view (x, y) of trajectories and loop edges as a PNG drawn by gnuplot (Debian:
 * gnuplot-nox): axes in meters with equal aspect, a legend naming each line, a title.
 */
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

namespace pcl {
namespace phaser {
namespace graph {

/** \brief One line of a top view and its legend entry, in world x, y (meters). */
struct Series {
  std::string title; ///< the legend entry
  std::vector<Eigen::Vector2d> points;
  std::string color = "#000000"; ///< "#rrggbb"
  double width = 2.0;            ///< gnuplot line width
  bool connected = true; ///< false: segments between consecutive pairs of points
};

/** \brief Draw \a series, in order (the first underneath), as a \a size x \a size PNG
 * at \a path with gnuplot: x to the right and y up in meters, equal aspect, a legend
 * below, \a title on top ('\\n' breaks lines). The data and script go to a temporary
 * directory (removed after); gnuplot, found on PATH, runs there as a child process
 * without a shell, and no file name enters its script. \return the reason on failure
 * (gnuplot missing or failing: with the Debian package to install, gnuplot-nox), else
 * empty */
std::string writeTopView(const std::string& path, const std::string& title,
                         const std::vector<Series>& series, int size = 900);

} // namespace graph
} // namespace phaser
} // namespace pcl
