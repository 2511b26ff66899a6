/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_bench objects: the global aligners on partial range scans of an object,
 * the Stanford bunny views of object/stanford_bunny, against the poses of Stanford's
 * bun.conf.
 *
 * bun.conf stores each view's rotation transposed: a line "bmesh <file> tx ty tz qx qy
 * qz qw" means p_bun000 = R(q)^T p + t. The parsing is header-only here so that the
 * tests can check it without the binary.
 */
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <sstream>
#include <string>

namespace pcl::phaser {
namespace bench {

/** \brief A view of bun.conf: its file and T_bun000_view. */
struct ObjectView {
  std::string file;
  Eigen::Matrix4d pose = Eigen::Matrix4d::Identity(); ///< T_bun000_view
};

/** \brief Parses a "bmesh <file> tx ty tz qx qy qz qw" line of bun.conf into \a view
 * (T_bun000_view = [R(q)^T | t]); false for any other line (camera, blank,
 * malformed). */
inline bool parseConfLine(const std::string& line, ObjectView& view)
{
  std::istringstream in(line);
  std::string kind, rest;
  double t[3], q[4];
  if (!(in >> kind >> view.file >> t[0] >> t[1] >> t[2] >> q[0] >> q[1] >> q[2] >>
        q[3]) ||
      kind != "bmesh" || (in >> rest))
    return false;
  const Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);
  if (!(rotation.norm() > 0.0))
    return false;
  view.pose.setIdentity();
  view.pose.topLeftCorner<3, 3>() =
      rotation.normalized().toRotationMatrix().transpose();
  view.pose.topRightCorner<3, 1>() = Eigen::Vector3d(t[0], t[1], t[2]);
  return true;
}

/** \brief T_target_source of two views: T_bun000_target^-1 * T_bun000_source. */
inline Eigen::Matrix4d objectTruth(const ObjectView& source, const ObjectView& target)
{
  return target.pose.inverse() * source.pose;
}

} // namespace bench
} // namespace pcl::phaser
