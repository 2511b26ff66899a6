/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * A 3-D pose graph in g2o's text format (VERTEX_SE3:QUAT, EDGE_SE3:QUAT, FIX), as
 * pcl_phaser_batch --g2o --odometry writes it, optimized with Ceres.
 */
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <map>
#include <set>
#include <string>
#include <vector>

namespace pcl {
namespace phaser {
namespace graph {

/** \brief One EDGE_SE3:QUAT: the pose of vertex \a to in the frame of \a from. */
struct Edge {
  int from = 0, to = 0;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  /** of g2o's error (translation, quaternion x y z of measurement^-1 * estimate) */
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Identity();
  bool odometry = false; ///< between consecutive vertices (to = from + 1): drawn apart
};

/** \brief A pose graph: vertices T_world_vertex by id, edges, fixed vertices. */
struct PoseGraph {
  std::map<int, Eigen::Isometry3d> vertices;
  std::vector<Edge> edges;
  std::set<int> fixed;
};

/** \brief Read a g2o file. \return the reason on failure (unreadable, a malformed or
 *  unknown line, an edge or FIX naming a missing vertex, an information matrix that is
 *  not positive definite), else empty */
std::string readG2o(const std::string& path, PoseGraph& graph);

/** \brief The robust loss of the edges. */
enum class Loss { None, Huber, Cauchy };

/** \brief Optimize the vertices of \a graph in place (the fixed ones, or the first
 *  when none is fixed, held); \a loss applies to every edge, with scale 3.55 on the
 *  whitened error (chi-square(6)'s 95 % point). \return the reason on failure, else
 *  empty */
std::string optimize(PoseGraph& graph, Loss loss, std::string* summary = nullptr);

/** \brief Make the odometry drift, as a dead-reckoning sensor would: each edge from a
 *  vertex to the next (the odometry edges of pcl_phaser_batch --odometry) gets its
 *  translation scaled by 1 + \a scale_per_step and a heading bias of \a deg_per_step
 *  degrees (about the vertex's z axis, before the step); the vertices after the first
 *  become the chain of these edges from it. Loop edges, information and FIX stay.
 *  \return the reason on failure (a vertex without exactly one edge to the next id),
 *  else empty */
std::string driftOdometry(PoseGraph& graph, double deg_per_step, double scale_per_step);

/** \brief The vertices as a poses file: per vertex, in id order, the 12 numbers of its
 *  row-major 3x4 T_world_vertex (as pcl_phaser_batch --poses reads). */
std::string posesText(const PoseGraph& graph);

/** \brief Root mean square of the distances between the positions of \a a and \a b
 *  after the rigid motion that best aligns them (Horn), over the ids both hold. */
double trajectoryError(const std::map<int, Eigen::Isometry3d>& a,
                       const std::map<int, Eigen::Isometry3d>& b);

} // namespace graph
} // namespace phaser
} // namespace pcl
