/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "pose_graph.h"
#include "text_lines.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include <ceres/ceres.h>
#include <cmath>
#include <iterator>
#include <limits>
#include <memory>
#include <sstream>

namespace pcl {
namespace phaser {
namespace graph {

namespace {

/** Scale of the robust loss on the whitened 6-D error: the 95 % point of chi-square(6)
 *  is 3.55^2, so consistent edges stay in the quadratic part. */
constexpr double kRobustScale = 3.55;

/** g2o's EDGE_SE3:QUAT error, whitened: sqrt_information * (translation, quaternion
 *  x y z) of Z^-1 * T_a^-1 * T_b, the quaternion taken with w >= 0. */
struct EdgeError {
  Eigen::Vector3d t_z;
  Eigen::Quaterniond q_z;
  Eigen::Matrix<double, 6, 6> sqrt_information;

  template <typename T>
  bool operator()(const T* ta, const T* qa, const T* tb, const T* qb, T* out) const
  {
    using Vec3 = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Vec3> t_a(ta), t_b(tb);
    const Eigen::Map<const Eigen::Quaternion<T>> q_a(qa), q_b(qb);
    const Eigen::Quaternion<T> q_a_inverse = q_a.conjugate();
    const Eigen::Quaternion<T> q_ab = q_a_inverse * q_b;
    const Vec3 t_ab = q_a_inverse * (t_b - t_a);
    const Eigen::Quaternion<T> q_zi = q_z.conjugate().template cast<T>();
    const Eigen::Quaternion<T> q_e = q_zi * q_ab;
    const Vec3 t_e = q_zi * (t_ab - t_z.template cast<T>());
    const T sign = q_e.w() < T(0) ? T(-1) : T(1);
    Eigen::Matrix<T, 6, 1> r;
    r << t_e, sign * q_e.vec();
    Eigen::Map<Eigen::Matrix<T, 6, 1>> residual(out);
    residual = sqrt_information.template cast<T>() * r;
    return true;
  }
};

bool readEdge(std::istringstream& fields, Edge& e)
{
  double x, y, z, qx, qy, qz, qw;
  if (!(fields >> e.from >> e.to >> x >> y >> z >> qx >> qy >> qz >> qw))
    return false;
  e.translation = {x, y, z};
  e.rotation = Eigen::Quaterniond(qw, qx, qy, qz);
  if (e.from == e.to || !e.rotation.coeffs().allFinite() ||
      !(e.rotation.norm() > 0.5) || !e.translation.allFinite())
    return false;
  e.rotation.normalize();
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j) {
      if (!(fields >> e.information(i, j)) || !std::isfinite(e.information(i, j)))
        return false;
      e.information(j, i) = e.information(i, j);
    }
  e.odometry = static_cast<long long>(e.to) == static_cast<long long>(e.from) + 1;
  return Eigen::LLT<Eigen::Matrix<double, 6, 6>>(e.information).info() ==
         Eigen::Success;
}

bool readVertex(std::istringstream& fields, PoseGraph& graph)
{
  int id;
  double x, y, z, qx, qy, qz, qw;
  if (!(fields >> id >> x >> y >> z >> qx >> qy >> qz >> qw))
    return false;
  const Eigen::Quaterniond q(qw, qx, qy, qz);
  if (!q.coeffs().allFinite() || !(q.norm() > 0.5) ||
      !Eigen::Vector3d(x, y, z).allFinite())
    return false;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return graph.vertices.emplace(id, T).second;
}

} // namespace

std::string readG2o(const std::string& path, PoseGraph& graph)
{
  const std::string error = forEachLine(path, [&](const std::string& line, int) {
    std::istringstream fields(line);
    std::string tag;
    int id = 0;
    Edge edge;
    fields >> tag;
    if (tag == "VERTEX_SE3:QUAT") {
      if (!readVertex(fields, graph))
        return "expected VERTEX_SE3:QUAT id x y z qx qy qz qw, a new id";
    } else if (tag == "EDGE_SE3:QUAT") {
      if (!readEdge(fields, edge))
        return "expected EDGE_SE3:QUAT i j x y z qx qy qz qw (i != j) and 21 "
               "information entries (positive definite)";
      graph.edges.push_back(edge);
    } else if (tag == "FIX" && fields >> id) {
      graph.fixed.insert(id);
    } else
      return "not a VERTEX_SE3:QUAT, EDGE_SE3:QUAT or FIX line";
    return "";
  });
  if (!error.empty())
    return error;
  for (const Edge& e : graph.edges)
    if (!graph.vertices.count(e.from) || !graph.vertices.count(e.to))
      return "'" + path + "': edge " + std::to_string(e.from) + " " +
             std::to_string(e.to) + " names a missing vertex";
  for (const int id : graph.fixed)
    if (!graph.vertices.count(id))
      return "'" + path + "': FIX " + std::to_string(id) + " names a missing vertex";
  if (graph.vertices.empty())
    return "'" + path + "' holds no vertex";
  return {};
}

std::string optimize(PoseGraph& graph, Loss loss, std::string* summary)
{
  struct Block {
    Eigen::Vector3d t;
    Eigen::Quaterniond q;
  };
  std::map<int, Block> blocks;
  for (const auto& [id, T] : graph.vertices)
    blocks[id] = {T.translation(), Eigen::Quaterniond(T.linear())};
  ceres::Problem problem;
  for (const Edge& e : graph.edges) {
    Block &a = blocks.at(e.from), &b = blocks.at(e.to);
    const Eigen::Matrix<double, 6, 6> S =
        Eigen::LLT<Eigen::Matrix<double, 6, 6>>(e.information).matrixU();
    auto* cost = new ceres::AutoDiffCostFunction<EdgeError, 6, 3, 4, 3, 4>(
        new EdgeError{e.translation, e.rotation, S});
    ceres::LossFunction* robust = nullptr;
    if (loss == Loss::Huber)
      robust = new ceres::HuberLoss(kRobustScale);
    else if (loss == Loss::Cauchy)
      robust = new ceres::CauchyLoss(kRobustScale);
    problem.AddResidualBlock(cost, robust, a.t.data(), a.q.coeffs().data(), b.t.data(),
                             b.q.coeffs().data());
  }
  for (auto& [id, block] : blocks)
    if (problem.HasParameterBlock(block.q.coeffs().data()))
      problem.SetManifold(block.q.coeffs().data(), new ceres::EigenQuaternionManifold);
  const bool hold_first = graph.fixed.empty();
  for (auto& [id, block] : blocks)
    if ((graph.fixed.count(id) || (hold_first && id == blocks.begin()->first)) &&
        problem.HasParameterBlock(block.t.data())) {
      problem.SetParameterBlockConstant(block.t.data());
      problem.SetParameterBlockConstant(block.q.coeffs().data());
    }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = 200;
  ceres::Solver::Summary result;
  ceres::Solve(options, &problem, &result);
  if (summary)
    *summary = result.BriefReport();
  if (!result.IsSolutionUsable())
    return "the optimization failed: " + result.message;
  for (auto& [id, T] : graph.vertices) {
    T.linear() = blocks.at(id).q.normalized().toRotationMatrix();
    T.translation() = blocks.at(id).t;
  }
  return {};
}

std::string driftOdometry(PoseGraph& graph, double deg_per_step, double scale_per_step)
{
  std::map<int, Edge*> steps;
  for (Edge& e : graph.edges)
    if (e.odometry && !steps.emplace(e.from, &e).second)
      return "two edges from vertex " + std::to_string(e.from) + " to the next";
  const Eigen::Isometry3d bias(
      Eigen::AngleAxisd(deg_per_step * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
  for (auto at = graph.vertices.begin(), next = std::next(at);
       next != graph.vertices.end(); ++at, ++next) {
    const auto step = steps.find(at->first);
    if (static_cast<long long>(next->first) != at->first + 1LL || step == steps.end())
      return "no odometry edge from vertex " + std::to_string(at->first) +
             " to the next (pcl_phaser_batch --odometry writes them)";
    Edge& e = *step->second;
    const Eigen::Isometry3d drifted =
        bias * Eigen::Translation3d((1.0 + scale_per_step) * e.translation) *
        e.rotation;
    e.translation = drifted.translation();
    e.rotation = Eigen::Quaterniond(drifted.linear()).normalized();
    next->second = at->second * drifted;
  }
  return {};
}

std::string posesText(const PoseGraph& graph)
{
  std::ostringstream out;
  out.precision(17);
  for (const auto& [id, T] : graph.vertices) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        out << (r || c ? " " : "") << T.matrix()(r, c);
    out << "\n";
  }
  return out.str();
}

double trajectoryError(const std::map<int, Eigen::Isometry3d>& a,
                       const std::map<int, Eigen::Isometry3d>& b)
{
  std::vector<int> ids;
  for (const auto& [id, T] : a)
    if (b.count(id))
      ids.push_back(id);
  if (ids.size() < 3)
    return std::numeric_limits<double>::quiet_NaN();
  Eigen::Matrix3Xd pa(3, ids.size()), pb(3, ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k) {
    pa.col(static_cast<Eigen::Index>(k)) = a.at(ids[k]).translation();
    pb.col(static_cast<Eigen::Index>(k)) = b.at(ids[k]).translation();
  }
  const Eigen::Matrix4d M = Eigen::umeyama(pa, pb, false);
  const Eigen::Matrix3Xd moved =
      (M.topLeftCorner<3, 3>() * pa).colwise() + M.topRightCorner<3, 1>();
  return std::sqrt((moved - pb).colwise().squaredNorm().mean());
}

} // namespace graph
} // namespace phaser
} // namespace pcl
