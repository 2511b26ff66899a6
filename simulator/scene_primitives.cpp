// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
#include "scene_primitives.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace pcl {
namespace phaser {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kParallel = 1e-15; // |direction component| below which it counts as 0

/** \brief World vector -> the primitive's yawed local frame (z unchanged). */
inline Eigen::Vector3d toLocal(const Eigen::Vector2d& heading, const Eigen::Vector3d& v)
{
  return {heading.x() * v.x() + heading.y() * v.y(),
          -heading.y() * v.x() + heading.x() * v.y(), v.z()};
}

/** \brief Local vector -> world. */
inline Eigen::Vector3d toWorld(const Eigen::Vector2d& heading, const Eigen::Vector3d& v)
{
  return {heading.x() * v.x() - heading.y() * v.y(),
          heading.y() * v.x() + heading.x() * v.y(), v.z()};
}

bool intersectBox(const ScenePrimitive& box, const Eigen::Vector3d& origin,
                  const Eigen::Vector3d& direction, double t_min, double t_max,
                  double& t, Eigen::Vector3d& normal)
{
  const Eigen::Vector3d o = toLocal(box.heading, origin - box.center);
  const Eigen::Vector3d d = toLocal(box.heading, direction);
  const Eigen::Vector3d& h = box.half_extent;
  double t_near = -std::numeric_limits<double>::infinity();
  double t_far = std::numeric_limits<double>::infinity();
  int axis_near = 0, axis_far = 0;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < kParallel) {
      if (std::abs(o[i]) > h[i])
        return false;
      continue;
    }
    const double inv = 1.0 / d[i];
    double t1 = (-h[i] - o[i]) * inv;
    double t2 = (h[i] - o[i]) * inv;
    if (t1 > t2)
      std::swap(t1, t2);
    if (t1 > t_near) {
      t_near = t1;
      axis_near = i;
    }
    if (t2 < t_far) {
      t_far = t2;
      axis_far = i;
    }
  }
  if (t_near > t_far)
    return false;
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  if (t_near > t_min && t_near < t_max) {
    t = t_near;
    n[axis_near] = d[axis_near] > 0.0 ? -1.0 : 1.0;
  } else if (t_far > t_min && t_far < t_max) {
    t = t_far;
    n[axis_far] = d[axis_far] > 0.0 ? 1.0 : -1.0;
  } else
    return false;
  normal = toWorld(box.heading, n);
  return true;
}

bool intersectCylinder(const ScenePrimitive& cylinder, const Eigen::Vector3d& origin,
                       const Eigen::Vector3d& direction, double t_min, double t_max,
                       double& t, Eigen::Vector3d& normal)
{
  const Eigen::Vector3d p = origin - cylinder.center;
  const Eigen::Vector3d& d = direction;
  const double radius = cylinder.half_extent.x();
  const double half_height = cylinder.half_extent.z();
  double best = t_max;
  bool found = false;
  const double a = d.x() * d.x() + d.y() * d.y();
  if (a > kParallel) {
    const double b = p.x() * d.x() + p.y() * d.y();
    const double c = p.x() * p.x() + p.y() * p.y() - radius * radius;
    const double disc = b * b - a * c;
    if (disc >= 0.0) {
      const double root = std::sqrt(disc);
      for (const double ti : {(-b - root) / a, (-b + root) / a}) {
        if (ti > t_min && ti < best && std::abs(p.z() + ti * d.z()) <= half_height) {
          best = ti;
          normal =
              Eigen::Vector3d(p.x() + ti * d.x(), p.y() + ti * d.y(), 0.0) / radius;
          found = true;
          break; // the roots are ascending
        }
      }
    }
  }
  if (std::abs(d.z()) > kParallel) {
    for (const double cap : {half_height, -half_height}) {
      const double ti = (cap - p.z()) / d.z();
      if (ti > t_min && ti < best) {
        const double x = p.x() + ti * d.x(), y = p.y() + ti * d.y();
        if (x * x + y * y <= radius * radius) {
          best = ti;
          normal = Eigen::Vector3d(0.0, 0.0, cap > 0.0 ? 1.0 : -1.0);
          found = true;
        }
      }
    }
  }
  if (found)
    t = best;
  return found;
}

bool intersectEllipsoid(const ScenePrimitive& ellipsoid, const Eigen::Vector3d& origin,
                        const Eigen::Vector3d& direction, double t_min, double t_max,
                        double& t, Eigen::Vector3d& normal)
{
  const Eigen::Vector3d& axes = ellipsoid.half_extent;
  const Eigen::Vector3d o = toLocal(ellipsoid.heading, origin - ellipsoid.center);
  const Eigen::Vector3d d = toLocal(ellipsoid.heading, direction);
  const Eigen::Vector3d q = o.cwiseQuotient(axes);
  const Eigen::Vector3d e = d.cwiseQuotient(axes);
  const double a = e.squaredNorm();
  const double b = q.dot(e);
  const double c = q.squaredNorm() - 1.0;
  const double disc = b * b - a * c;
  if (disc < 0.0)
    return false;
  const double root = std::sqrt(disc);
  for (const double ti : {(-b - root) / a, (-b + root) / a}) {
    if (ti > t_min && ti < t_max) {
      t = ti;
      const Eigen::Vector3d local = o + ti * d;
      normal = toWorld(ellipsoid.heading,
                       local.cwiseQuotient(axes.cwiseProduct(axes)).normalized());
      return true;
    }
  }
  return false;
}

/** \brief Draws from a std::mt19937 through its raw, standard-defined output only. */
class Draw {
public:
  explicit Draw(unsigned seed)
      : rng_(seed)
  {
  }
  /** \brief Uniform in [lo, hi). */
  double uniform(double lo, double hi)
  {
    return lo + (hi - lo) * (static_cast<double>(rng_()) / 4294967296.0);
  }
  /** \brief True with probability p. */
  bool chance(double p) { return uniform(0.0, 1.0) < p; }

private:
  std::mt19937 rng_;
};

/** \brief Bounding circles of the objects placed so far, for rejection sampling. */
class Layout {
public:
  Layout(double half_extent, double clear_radius)
      : half_(half_extent)
      , clear_radius_(clear_radius)
  {
  }
  /** \brief Can a disc of the radius sit at (x, y), gap meters from everything? */
  bool fits(double x, double y, double radius, double gap) const
  {
    if (std::abs(x) > half_ - radius || std::abs(y) > half_ - radius ||
        std::hypot(x, y) < clear_radius_ + radius)
      return false;
    for (const Eigen::Vector3d& c : circles_)
      if (std::hypot(x - c.x(), y - c.y()) < radius + c.z() + gap)
        return false;
    return true;
  }
  void add(double x, double y, double radius) { circles_.emplace_back(x, y, radius); }
  double half() const { return half_; }

private:
  double half_, clear_radius_;
  std::vector<Eigen::Vector3d> circles_;
};

/** \brief Roads as lines of the ground texture: y = kRoadAY (along x), x = kRoadBX. */
constexpr double kRoadAY = 2.0, kRoadAHalfWidth = 3.5;
constexpr double kRoadBX = -3.0, kRoadBHalfWidth = 3.0;

void addBuildings(const SceneParameters& params, Draw& draw, Layout& layout,
                  std::vector<ScenePrimitive>& out)
{
  const double sector_offset = draw.uniform(0.0, 2.0 * kPi);
  for (int k = 0; k < params.buildings; ++k) {
    for (int attempt = 0; attempt < 80; ++attempt) {
      const double shrink = 1.0 - 0.008 * attempt;
      const double a = draw.uniform(5.0, 25.0) * shrink;
      const double b = draw.uniform(5.0, 25.0) * shrink;
      const double height = draw.uniform(4.0, 20.0);
      const double yaw = draw.uniform(0.0, kPi);
      const double reflectivity = draw.uniform(0.3, 0.7);
      const bool l_shape = draw.chance(0.4);
      // Wing of an L: attached to the +y side of the main block, flush with its +x end.
      const double wing_hx = draw.uniform(0.3, 0.5) * 0.5 * a;
      const double wing_hy = draw.uniform(2.5, 6.0);
      const double wing_height = height * draw.uniform(0.5, 1.0);
      const Eigen::Vector2d wing_center(0.5 * a - wing_hx, 0.5 * b - 0.5 + wing_hy);
      double radius = 0.5 * std::hypot(a, b);
      if (l_shape)
        radius = std::max(radius, std::hypot(std::abs(wing_center.x()) + wing_hx,
                                             std::abs(wing_center.y()) + wing_hy));
      const double angle =
          sector_offset + 2.0 * kPi * (k + draw.uniform(0.15, 0.85)) / params.buildings;
      const double lo = params.clear_radius + radius + 1.0;
      const double hi = layout.half() - radius;
      if (lo > hi)
        continue;
      const double dist = draw.uniform(lo, hi);
      const double x = dist * std::cos(angle), y = dist * std::sin(angle);
      if (!layout.fits(x, y, radius, 2.0))
        continue;
      layout.add(x, y, radius);
      out.push_back(makeBox({x, y, 0.5 * height}, {0.5 * a, 0.5 * b, 0.5 * height}, yaw,
                            reflectivity));
      if (l_shape) {
        const double c = std::cos(yaw), s = std::sin(yaw);
        const Eigen::Vector3d center(x + c * wing_center.x() - s * wing_center.y(),
                                     y + s * wing_center.x() + c * wing_center.y(),
                                     0.5 * wing_height);
        out.push_back(
            makeBox(center, {wing_hx, wing_hy, 0.5 * wing_height}, yaw,
                    std::clamp(reflectivity + draw.uniform(-0.1, 0.1), 0.0, 1.0)));
      }
      break;
    }
  }
}

/** \brief Place a disc of the radius: near a road edge with probability road_chance
 * (offset meters from the road's center line), anywhere otherwise. */
bool placeDisc(Draw& draw, const Layout& layout, double radius, double gap,
               double road_chance, double offset, double& x, double& y, double& yaw)
{
  for (int attempt = 0; attempt < 60; ++attempt) {
    const double along = draw.uniform(-layout.half(), layout.half());
    const double side = draw.chance(0.5) ? 1.0 : -1.0;
    const double pick = draw.uniform(0.0, 1.0);
    yaw = draw.uniform(0.0, 2.0 * kPi);
    if (pick < 0.5 * road_chance) {
      x = along;
      y = kRoadAY + side * (kRoadAHalfWidth + offset);
      yaw = side > 0.0 ? 0.0 : kPi;
    } else if (pick < road_chance) {
      x = kRoadBX + side * (kRoadBHalfWidth + offset);
      y = along;
      yaw = side > 0.0 ? 0.5 * kPi : 1.5 * kPi;
    } else {
      x = draw.uniform(-layout.half(), layout.half());
      y = draw.uniform(-layout.half(), layout.half());
    }
    if (layout.fits(x, y, radius, gap))
      return true;
  }
  return false;
}

} // namespace

ScenePrimitive makeBox(const Eigen::Vector3d& center,
                       const Eigen::Vector3d& half_extent, double yaw,
                       double reflectivity)
{
  ScenePrimitive p;
  p.shape = PrimitiveShape::BOX;
  p.center = center;
  p.half_extent = half_extent;
  p.heading = Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
  p.reflectivity = reflectivity;
  return p;
}

ScenePrimitive makeCylinder(double x, double y, double z_min, double z_max,
                            double radius, double reflectivity)
{
  ScenePrimitive p;
  p.shape = PrimitiveShape::CYLINDER;
  p.center = Eigen::Vector3d(x, y, 0.5 * (z_min + z_max));
  p.half_extent = Eigen::Vector3d(radius, radius, 0.5 * (z_max - z_min));
  p.reflectivity = reflectivity;
  return p;
}

ScenePrimitive makeEllipsoid(const Eigen::Vector3d& center,
                             const Eigen::Vector3d& semi_axes, double yaw,
                             double reflectivity)
{
  ScenePrimitive p = makeBox(center, semi_axes, yaw, reflectivity);
  p.shape = PrimitiveShape::ELLIPSOID;
  return p;
}

bool intersectRay(const ScenePrimitive& primitive, const Eigen::Vector3d& origin,
                  const Eigen::Vector3d& direction, double t_min, double t_max,
                  double& t, Eigen::Vector3d& normal)
{
  switch (primitive.shape) {
  case PrimitiveShape::BOX:
    return intersectBox(primitive, origin, direction, t_min, t_max, t, normal);
  case PrimitiveShape::CYLINDER:
    return intersectCylinder(primitive, origin, direction, t_min, t_max, t, normal);
  case PrimitiveShape::ELLIPSOID:
    return intersectEllipsoid(primitive, origin, direction, t_min, t_max, t, normal);
  }
  return false;
}

double distanceToPrimitive(const ScenePrimitive& primitive,
                           const Eigen::Vector3d& point)
{
  const Eigen::Vector3d& h = primitive.half_extent;
  switch (primitive.shape) {
  case PrimitiveShape::BOX: {
    const Eigen::Vector3d p = toLocal(primitive.heading, point - primitive.center);
    return (p.cwiseAbs() - h).cwiseMax(0.0).norm();
  }
  case PrimitiveShape::CYLINDER: {
    const Eigen::Vector3d p = point - primitive.center;
    const double radial = std::max(0.0, std::hypot(p.x(), p.y()) - h.x());
    const double vertical = std::max(0.0, std::abs(p.z()) - h.z());
    return std::hypot(radial, vertical);
  }
  case PrimitiveShape::ELLIPSOID: {
    const Eigen::Vector3d p = toLocal(primitive.heading, point - primitive.center);
    const double scaled = p.cwiseQuotient(h).norm();
    return std::max({0.0, p.norm() - h.maxCoeff(), (scaled - 1.0) * h.minCoeff()});
  }
  }
  return 0.0;
}

Eigen::Vector4d footprintBounds(const ScenePrimitive& primitive)
{
  const double c = std::abs(primitive.heading.x()), s = std::abs(primitive.heading.y());
  const Eigen::Vector3d& h = primitive.half_extent;
  double ex = h.x(), ey = h.y();
  if (primitive.shape == PrimitiveShape::BOX) {
    ex = c * h.x() + s * h.y();
    ey = s * h.x() + c * h.y();
  } else if (primitive.shape == PrimitiveShape::ELLIPSOID) {
    ex = std::hypot(c * h.x(), s * h.y());
    ey = std::hypot(s * h.x(), c * h.y());
  }
  const Eigen::Vector3d& m = primitive.center;
  return {m.x() - ex, m.y() - ey, m.x() + ex, m.y() + ey};
}

double topHeight(const ScenePrimitive& primitive)
{
  return primitive.center.z() + primitive.half_extent.z();
}

double groundReflectivity(double x, double y)
{
  const double ay = std::abs(y - kRoadAY), bx = std::abs(x - kRoadBX);
  if (ay < kRoadAHalfWidth || bx < kRoadBHalfWidth) {
    // Dashed center line on road A, solid edge lines on both, asphalt elsewhere.
    if (ay < 0.075 && bx > kRoadBHalfWidth && std::fmod(x + 3000.0, 6.0) < 3.0)
      return 0.8;
    if ((ay > kRoadAHalfWidth - 0.3 && ay < kRoadAHalfWidth - 0.15 &&
         bx > kRoadBHalfWidth) ||
        (bx > kRoadBHalfWidth - 0.3 && bx < kRoadBHalfWidth - 0.15 &&
         ay > kRoadAHalfWidth))
      return 0.75;
    return 0.12;
  }
  // Gravel and grass patches.
  return 0.24 + 0.06 * std::sin(0.31 * x + 0.7) * std::cos(0.23 * y - 0.4);
}

namespace {

/** Walls, cars and poles, in that order of draws. */
void addStreetFurniture(const SceneParameters& params, Draw& draw, Layout& layout,
                        std::vector<ScenePrimitive>& out)
{
  double x = 0.0, y = 0.0, yaw = 0.0;
  for (int i = 0; i < params.walls; ++i) {
    const double half_length = draw.uniform(4.0, 15.0);
    const double height = draw.uniform(1.0, 2.5);
    const double reflectivity = draw.uniform(0.35, 0.6);
    if (!placeDisc(draw, layout, half_length, 1.0, 0.3, 2.0, x, y, yaw))
      continue;
    layout.add(x, y, half_length);
    out.push_back(makeBox({x, y, 0.5 * height}, {half_length, 0.15, 0.5 * height}, yaw,
                          reflectivity));
  }
  for (int i = 0; i < params.cars; ++i) {
    const double body_reflectivity = draw.uniform(0.85, 0.95);
    if (!placeDisc(draw, layout, 2.4, 0.5, 0.6, -1.3, x, y, yaw))
      continue;
    layout.add(x, y, 2.4);
    out.push_back(makeBox({x, y, 0.65}, {2.2, 0.9, 0.4}, yaw, body_reflectivity));
    const double c = std::cos(yaw), s = std::sin(yaw);
    out.push_back(makeBox({x - 0.2 * c, y - 0.2 * s, 1.3}, {1.2, 0.8, 0.25}, yaw, 0.3));
  }
  for (int i = 0; i < params.poles; ++i) {
    const double radius = draw.uniform(0.08, 0.2);
    const double height = draw.uniform(4.0, 9.0);
    const double reflectivity = draw.uniform(0.75, 0.9);
    if (!placeDisc(draw, layout, radius, 0.5, 0.5, 1.0, x, y, yaw))
      continue;
    layout.add(x, y, radius);
    out.push_back(makeCylinder(x, y, 0.0, height, radius, reflectivity));
  }
}

/** Trees and bushes, in that order of draws. */
void addVegetation(const SceneParameters& params, Draw& draw, Layout& layout,
                   std::vector<ScenePrimitive>& out)
{
  double x = 0.0, y = 0.0, yaw = 0.0;
  for (int i = 0; i < params.trees; ++i) {
    const double trunk_radius = draw.uniform(0.15, 0.35);
    const double trunk_height = draw.uniform(2.0, 4.5);
    const Eigen::Vector3d crown(draw.uniform(1.5, 3.5), draw.uniform(1.5, 3.5),
                                draw.uniform(1.2, 3.0));
    const double trunk_reflectivity = draw.uniform(0.35, 0.5);
    const double crown_reflectivity = draw.uniform(0.35, 0.45);
    const double radius = std::max(crown.x(), crown.y());
    if (!placeDisc(draw, layout, radius, 0.0, 0.3, 3.5, x, y, yaw))
      continue;
    layout.add(x, y, radius);
    const double crown_z = trunk_height + 0.6 * crown.z();
    out.push_back(makeCylinder(x, y, 0.0, crown_z, trunk_radius, trunk_reflectivity));
    out.push_back(makeEllipsoid({x, y, crown_z}, crown, yaw, crown_reflectivity));
  }
  for (int i = 0; i < params.bushes; ++i) {
    const Eigen::Vector3d axes(draw.uniform(0.6, 1.6), draw.uniform(0.6, 1.6),
                               draw.uniform(0.5, 1.0));
    const double center_z = draw.uniform(0.2, 0.6);
    const double reflectivity = draw.uniform(0.4, 0.5);
    const double radius = std::max(axes.x(), axes.y());
    if (!placeDisc(draw, layout, radius, 0.0, 0.2, 2.0, x, y, yaw))
      continue;
    layout.add(x, y, radius);
    out.push_back(makeEllipsoid({x, y, center_z}, axes, yaw, reflectivity));
  }
}

} // namespace

std::vector<ScenePrimitive> generateScene(const SceneParameters& params)
{
  if (params.buildings < 0 || params.poles < 0 || params.trees < 0 ||
      params.bushes < 0 || params.cars < 0 || params.walls < 0)
    throw std::invalid_argument("generateScene: object counts must be >= 0");
  if (!(params.extent > 2.0 * params.clear_radius + 20.0) || params.clear_radius < 0.0)
    throw std::invalid_argument(
        "generateScene: extent must exceed 2 * clear_radius + 20 m, clear_radius >= 0");
  Draw draw(params.seed);
  Layout layout(0.5 * params.extent, params.clear_radius);
  std::vector<ScenePrimitive> out;
  addBuildings(params, draw, layout, out);

  addStreetFurniture(params, draw, layout, out);
  addVegetation(params, draw, layout, out);
  return out;
}

namespace {
inline std::uint64_t splitMix(std::uint64_t z)
{
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}
} // namespace

std::uint64_t hashRandom(std::uint64_t seed, std::uint64_t index, std::uint64_t stream)
{
  return splitMix(splitMix(splitMix(seed) ^ index) ^
                  (stream * 0xD6E8FEB86659FD93ULL + 0x632BE59BD9B4E019ULL));
}

double hashGaussian(std::uint64_t seed, std::uint64_t index, std::uint64_t stream)
{
  const std::uint64_t r = hashRandom(seed, index, stream);
  const double u1 = (static_cast<double>(r >> 32) + 0.5) / 4294967296.0; // (0, 1)
  const double u2 = static_cast<double>(r & 0xFFFFFFFFULL) / 4294967296.0;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

} // namespace phaser
} // namespace pcl
