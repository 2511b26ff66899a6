// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
#include "scan_simulator.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcl {
namespace phaser {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
constexpr double kTMin = 1e-9;      // hits at or closer than this are ignored
constexpr double kParallel = 1e-15; // |direction component| below which it counts as 0
constexpr int kMaxCellsPerAxis = 512;

/** \brief One ray's outcome in the scan buffer. */
struct Return {
  float x, y, z, intensity;
  bool valid;
};

/** \brief The valid returns, in buffer order, as a dense unorganized cloud. */
pcl::PointCloud<pcl::PointXYZI> cloudOf(const std::vector<Return>& returns)
{
  pcl::PointCloud<pcl::PointXYZI> cloud;
  cloud.reserve(returns.size());
  for (const Return& r : returns) {
    if (!r.valid)
      continue;
    pcl::PointXYZI point;
    point.x = r.x;
    point.y = r.y;
    point.z = r.z;
    point.intensity = r.intensity;
    cloud.push_back(point);
  }
  cloud.width = static_cast<std::uint32_t>(cloud.size());
  cloud.height = 1;
  cloud.is_dense = true;
  return cloud;
}

void validate(const LidarParameters& lidar)
{
  if (lidar.beams < 1)
    throw std::invalid_argument("LidarParameters: beams must be >= 1");
  if (!(lidar.max_elevation_deg >= lidar.min_elevation_deg) ||
      !(lidar.min_elevation_deg >= -90.0) || !(lidar.max_elevation_deg <= 90.0))
    throw std::invalid_argument(
        "LidarParameters: need -90 <= min_elevation_deg <= max_elevation_deg <= 90");
  if (!(lidar.azimuth_step_deg > 0.0) || !(lidar.azimuth_step_deg <= 360.0))
    throw std::invalid_argument(
        "LidarParameters: azimuth_step_deg must be in (0, 360]");
  if (!(lidar.min_range >= 0.0) || !(lidar.max_range > lidar.min_range) ||
      !std::isfinite(lidar.max_range))
    throw std::invalid_argument("LidarParameters: need 0 <= min_range < max_range");
  if (!(lidar.range_noise >= 0.0) || !(lidar.intensity_noise >= 0.0) ||
      !std::isfinite(lidar.range_noise) || !std::isfinite(lidar.intensity_noise))
    throw std::invalid_argument("LidarParameters: noise must be finite and >= 0");
}

} // namespace

SimulatedScene::SimulatedScene(const SceneParameters& params)
    : SimulatedScene(generateScene(params), true)
{
}

SimulatedScene::SimulatedScene(std::vector<ScenePrimitive> primitives, bool with_ground)
    : primitives_(std::move(primitives))
    , with_ground_(with_ground)
{
  buildGrid();
}

void SimulatedScene::buildGrid()
{
  cell_start_.assign(1, 0);
  cell_items_.clear();
  grid_nx_ = grid_ny_ = 0;
  if (primitives_.empty())
    return;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector2d hi = -lo;
  top_ = -std::numeric_limits<double>::max();
  bottom_ = std::numeric_limits<double>::max();
  std::vector<Eigen::Vector4d> bounds;
  bounds.reserve(primitives_.size());
  for (const ScenePrimitive& p : primitives_) {
    bounds.push_back(footprintBounds(p));
    lo = lo.cwiseMin(bounds.back().head<2>());
    hi = hi.cwiseMax(bounds.back().tail<2>());
    top_ = std::max(top_, topHeight(p));
    bottom_ = std::min(bottom_, p.center.z() - p.half_extent.z());
  }
  // Pad a little so every footprint lies strictly inside the grid.
  lo -= Eigen::Vector2d::Constant(0.01);
  hi += Eigen::Vector2d::Constant(0.01);
  const Eigen::Vector2d size = hi - lo;
  cell_size_ =
      std::max({4.0, size.x() / kMaxCellsPerAxis, size.y() / kMaxCellsPerAxis});
  grid_min_ = lo;
  grid_nx_ = std::max(1, static_cast<int>(std::ceil(size.x() / cell_size_)));
  grid_ny_ = std::max(1, static_cast<int>(std::ceil(size.y() / cell_size_)));

  const auto cellRange = [&](const Eigen::Vector4d& b, int& x0, int& y0, int& x1,
                             int& y1) {
    x0 = std::clamp(static_cast<int>(std::floor((b[0] - lo.x()) / cell_size_)), 0,
                    grid_nx_ - 1);
    y0 = std::clamp(static_cast<int>(std::floor((b[1] - lo.y()) / cell_size_)), 0,
                    grid_ny_ - 1);
    x1 = std::clamp(static_cast<int>(std::floor((b[2] - lo.x()) / cell_size_)), 0,
                    grid_nx_ - 1);
    y1 = std::clamp(static_cast<int>(std::floor((b[3] - lo.y()) / cell_size_)), 0,
                    grid_ny_ - 1);
  };
  std::vector<int> counts(static_cast<std::size_t>(grid_nx_) * grid_ny_ + 1, 0);
  int x0, y0, x1, y1;
  for (const Eigen::Vector4d& b : bounds) {
    cellRange(b, x0, y0, x1, y1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        ++counts[static_cast<std::size_t>(y) * grid_nx_ + x + 1];
  }
  for (std::size_t i = 1; i < counts.size(); ++i)
    counts[i] += counts[i - 1];
  cell_start_ = counts;
  cell_items_.assign(static_cast<std::size_t>(counts.back()), 0);
  for (std::size_t k = 0; k < bounds.size(); ++k) {
    cellRange(bounds[k], x0, y0, x1, y1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        cell_items_[counts[static_cast<std::size_t>(y) * grid_nx_ + x]++] =
            static_cast<int>(k);
  }
}

bool SimulatedScene::castRay(const Eigen::Vector3d& origin,
                             const Eigen::Vector3d& direction, double max_range,
                             RayHit& hit) const
{
  const double norm = direction.norm();
  if (!(norm > 0.0) || !std::isfinite(norm))
    return false;
  return castUnitRay(origin, direction / norm, max_range, hit);
}

void SimulatedScene::intersectGround(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                                     Nearest& best) const
{
  if (!(with_ground_ && std::abs(d.z()) > kParallel))
    return;
  const double t = -o.z() / d.z();
  if (t > kTMin && t < best.t) {
    best.t = t;
    best.id = -1;
    best.normal = Eigen::Vector3d(0.0, 0.0, o.z() >= 0.0 ? 1.0 : -1.0);
  }
}

bool SimulatedScene::clipToGrid(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                                double& t_enter, double& t_leave) const
{
  bool in_grid = grid_nx_ > 0;
  const Eigen::Vector2d grid_max =
      grid_min_ + cell_size_ * Eigen::Vector2d(grid_nx_, grid_ny_);
  for (int a = 0; a < 2 && in_grid; ++a) {
    if (std::abs(d[a]) < kParallel) {
      in_grid = o[a] >= grid_min_[a] && o[a] <= grid_max[a];
      continue;
    }
    double ta = (grid_min_[a] - o[a]) / d[a], tb = (grid_max[a] - o[a]) / d[a];
    if (ta > tb)
      std::swap(ta, tb);
    t_enter = std::max(t_enter, ta);
    t_leave = std::min(t_leave, tb);
  }
  return (in_grid && t_enter <= t_leave);
}

void SimulatedScene::traverseGrid(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                                  double t_enter, double t_leave, Nearest& best) const
{
  int cell[2], step[2];
  double next[2], delta[2];
  for (int a = 0; a < 2; ++a) {
    const int n = a == 0 ? grid_nx_ : grid_ny_;
    const double p = o[a] + t_enter * d[a];
    cell[a] = std::clamp(static_cast<int>(std::floor((p - grid_min_[a]) / cell_size_)),
                         0, n - 1);
    if (d[a] > kParallel) {
      step[a] = 1;
      next[a] = (grid_min_[a] + (cell[a] + 1) * cell_size_ - o[a]) / d[a];
      delta[a] = cell_size_ / d[a];
    } else if (d[a] < -kParallel) {
      step[a] = -1;
      next[a] = (grid_min_[a] + cell[a] * cell_size_ - o[a]) / d[a];
      delta[a] = -cell_size_ / d[a];
    } else {
      step[a] = 0;
      next[a] = delta[a] = std::numeric_limits<double>::infinity();
    }
  }
  double t;
  Eigen::Vector3d normal;
  for (;;) {
    const std::size_t c = static_cast<std::size_t>(cell[1]) * grid_nx_ + cell[0];
    for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
      const int id = cell_items_[k];
      if (intersectRay(primitives_[id], o, d, kTMin, best.t, t, normal)) {
        best.t = t;
        best.id = id;
        best.normal = normal;
      }
    }
    const int a = next[0] < next[1] ? 0 : 1;
    const double exit = next[a];
    if (best.t <= exit || exit > t_leave)
      break;
    const double z = o.z() + exit * d.z();
    if ((d.z() > 0.0 && z > top_) || (d.z() < 0.0 && z < bottom_))
      break; // above or below every solid from here on
    cell[a] += step[a];
    next[a] += delta[a];
    if (cell[a] < 0 || cell[a] >= (a == 0 ? grid_nx_ : grid_ny_))
      break;
  }
}

bool SimulatedScene::castUnitRay(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                                 double max_range, RayHit& hit) const
{
  // Strict "< best" tests everywhere: nudge the limit so a hit at max_range counts.
  Nearest best;
  best.t = std::nextafter(max_range, std::numeric_limits<double>::infinity());
  intersectGround(o, d, best);
  // 2-D DDA through the grid cells the ray's xy projection crosses.
  double t_enter = 0.0, t_leave = best.t;
  if (clipToGrid(o, d, t_enter, t_leave))
    traverseGrid(o, d, t_enter, t_leave, best);
  if (best.id == -2)
    return false;
  hit.range = best.t;
  hit.point = o + best.t * d;
  hit.normal = best.normal;
  hit.primitive = best.id;
  hit.reflectivity = best.id >= 0 ? primitives_[best.id].reflectivity
                                  : groundReflectivity(hit.point.x(), hit.point.y());
  return true;
}

pcl::PointCloud<pcl::PointXYZI>
SimulatedScene::scan(const Eigen::Isometry3d& sensor_pose_in_world,
                     const LidarParameters& lidar) const
{
  validate(lidar);
  const int beams = lidar.beams;
  const int columns =
      std::max(1, static_cast<int>(std::ceil(360.0 / lidar.azimuth_step_deg - 1e-9)));
  std::vector<double> beam_cos(beams), beam_sin(beams);
  for (int b = 0; b < beams; ++b) {
    const double elevation =
        beams > 1
            ? lidar.min_elevation_deg +
                  b * (lidar.max_elevation_deg - lidar.min_elevation_deg) / (beams - 1)
            : lidar.min_elevation_deg;
    beam_cos[b] = std::cos(elevation * kDegToRad);
    beam_sin[b] = std::sin(elevation * kDegToRad);
  }
  const Eigen::Vector3d origin = sensor_pose_in_world.translation();
  const Eigen::Matrix3d rotation = sensor_pose_in_world.linear();
  // Look a few sigma past max_range: noise may bring a farther surface into range.
  const double search_range = lidar.max_range + 6.0 * lidar.range_noise;
  const std::uint64_t seed = lidar.noise_seed;

  std::vector<Return> returns(static_cast<std::size_t>(columns) * beams);
#ifdef _OPENMP
  const int threads = lidar.num_threads > 0 ? lidar.num_threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
#endif
  for (int j = 0; j < columns; ++j) {
    const double azimuth = j * lidar.azimuth_step_deg * kDegToRad;
    const double ca = std::cos(azimuth), sa = std::sin(azimuth);
    RayHit hit;
    for (int b = 0; b < beams; ++b) {
      const std::size_t index = static_cast<std::size_t>(j) * beams + b;
      Return& out = returns[index];
      out.valid = false;
      const Eigen::Vector3d dir_sensor(beam_cos[b] * ca, beam_cos[b] * sa, beam_sin[b]);
      const Eigen::Vector3d dir_world = rotation * dir_sensor;
      if (!castUnitRay(origin, dir_world, search_range, hit))
        continue;
      const double range = hit.range + lidar.range_noise * hashGaussian(seed, index, 0);
      if (!(range >= lidar.min_range && range <= lidar.max_range))
        continue;
      const double cos_incidence = std::abs(hit.normal.dot(dir_world));
      const double intensity = hit.reflectivity * (0.4 + 0.6 * cos_incidence) +
                               lidar.intensity_noise * hashGaussian(seed, index, 1);
      const Eigen::Vector3d p = range * dir_sensor;
      out.x = static_cast<float>(p.x());
      out.y = static_cast<float>(p.y());
      out.z = static_cast<float>(p.z());
      out.intensity = static_cast<float>(std::clamp(intensity, 0.0, 1.0));
      out.valid = true;
    }
  }

  return cloudOf(returns);
}

bool SimulatedScene::isFree(const Eigen::Vector3d& position, double clearance) const
{
  if (!position.allFinite() || (with_ground_ && !(position.z() > 0.0)))
    return false;
  for (const ScenePrimitive& p : primitives_)
    if (!(distanceToPrimitive(p, position) >= clearance))
      return false;
  return true;
}

Eigen::Isometry3d makeSensorPose(double x, double y, double yaw, double roll,
                                 double pitch, double height)
{
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  pose.translation() = Eigen::Vector3d(x, y, height);
  return pose;
}

ScanPair makeScanPair(const SimulatedScene& scene, const Eigen::Isometry3d& target_pose,
                      const Eigen::Isometry3d& source_pose,
                      const LidarParameters& lidar)
{
  ScanPair pair;
  pair.target_pose = target_pose;
  pair.source_pose = source_pose;
  pair.T_target_source = (target_pose.inverse() * source_pose).matrix();
  pair.target = scene.scan(target_pose, lidar);
  LidarParameters source_lidar = lidar;
  source_lidar.noise_seed = lidar.noise_seed ^ 0x9E3779B9u;
  pair.source = scene.scan(source_pose, source_lidar);
  return pair;
}

ScanPair makeDemoPair(unsigned seed, const LidarParameters& lidar)
{
  SceneParameters params;
  params.seed = seed;
  const SimulatedScene scene(params);
  std::mt19937 rng(seed ^ 0x2545F491u);
  const auto uniform = [&rng](double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng()) / 4294967296.0);
  };
  Eigen::Isometry3d target_pose = makeSensorPose(0.0, 0.0, 0.0);
  Eigen::Isometry3d source_pose = makeSensorPose(3.0, 0.0, 2.3);
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const double radius = 4.0 * std::sqrt(uniform(0.0, 1.0));
    const double angle = uniform(0.0, 2.0 * kPi);
    const double yaw = uniform(-kPi, kPi);
    const double offset = uniform(2.0, 4.0);
    const double offset_angle = uniform(0.0, 2.0 * kPi);
    const double turn = uniform(100.0, 160.0) * kDegToRad * (rng() & 1u ? 1.0 : -1.0);
    const double roll = uniform(-3.0, 3.0) * kDegToRad;
    const double pitch = uniform(-3.0, 3.0) * kDegToRad;
    const double x = radius * std::cos(angle), y = radius * std::sin(angle);
    const Eigen::Isometry3d t_pose = makeSensorPose(x, y, yaw);
    const Eigen::Isometry3d s_pose =
        makeSensorPose(x + offset * std::cos(offset_angle),
                       y + offset * std::sin(offset_angle), yaw + turn, roll, pitch);
    if (scene.isFree(t_pose.translation(), 1.5) &&
        scene.isFree(s_pose.translation(), 1.5)) {
      target_pose = t_pose;
      source_pose = s_pose;
      break;
    }
  }
  return makeScanPair(scene, target_pose, source_pose, lidar);
}

} // namespace phaser
} // namespace pcl
