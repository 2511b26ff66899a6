// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
// Solids of the procedural outdoor scene used by the LiDAR scan simulator: boxes,
// vertical cylinders and ellipsoids, their exact ray intersections, and the seeded
// scene generator.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl {
namespace phaser {

/** \brief Shape of a scene primitive. */
enum class PrimitiveShape {
  BOX,      ///< box with a vertical axis, yawed about z
  CYLINDER, ///< vertical cylinder of finite height, closed by two flat caps
  ELLIPSOID ///< ellipsoid whose semi-axes are local x, y, z, yawed about z
};

/** \brief One solid of a simulated scene, in world coordinates (z up, ground z = 0).
 *
 * Build them with makeBox(), makeCylinder() and makeEllipsoid().
 */
struct ScenePrimitive {
  /** \brief Which solid this is. */
  PrimitiveShape shape = PrimitiveShape::BOX;
  /** \brief Center of the solid (for a cylinder: the middle of its axis). */
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  /** \brief Box: half sizes along its local x, y, z; cylinder: (radius, radius, half
   * height); ellipsoid: semi-axes along its local x, y, z. */
  Eigen::Vector3d half_extent = Eigen::Vector3d::Ones();
  /** \brief Direction of the solid's local x axis in the world xy plane,
   * (cos yaw, sin yaw) for a rotation by yaw about z; unit length (cylinders: unused).
   */
  Eigen::Vector2d heading = Eigen::Vector2d::UnitX();
  /** \brief Reflectivity of the surface in [0, 1], the base of the returned intensity.
   */
  double reflectivity = 0.5;
};

/** \brief A box standing upright, rotated by yaw about z.
 * \param[in] center center of the box
 * \param[in] half_extent half sizes along the box's local x, y, z (all > 0)
 * \param[in] yaw rotation about z, radians
 * \param[in] reflectivity surface reflectivity in [0, 1]
 */
ScenePrimitive makeBox(const Eigen::Vector3d& center,
                       const Eigen::Vector3d& half_extent, double yaw,
                       double reflectivity);

/** \brief A vertical cylinder (pole, trunk) from z_min to z_max.
 * \param[in] x,y position of the axis
 * \param[in] z_min,z_max bottom and top heights (z_max > z_min)
 * \param[in] radius radius (> 0)
 * \param[in] reflectivity surface reflectivity in [0, 1]
 */
ScenePrimitive makeCylinder(double x, double y, double z_min, double z_max,
                            double radius, double reflectivity);

/** \brief An ellipsoid (tree crown, bush), rotated by yaw about z.
 * \param[in] center center
 * \param[in] semi_axes semi-axes along its local x, y, z (all > 0)
 * \param[in] yaw rotation about z, radians
 * \param[in] reflectivity surface reflectivity in [0, 1]
 */
ScenePrimitive makeEllipsoid(const Eigen::Vector3d& center,
                             const Eigen::Vector3d& semi_axes, double yaw,
                             double reflectivity);

/** \brief Nearest intersection of a ray with a primitive in the open interval
 * (t_min, t_max).
 *
 * A ray that starts inside a solid hits its inner surface.
 * \param[in] primitive the solid
 * \param[in] origin ray origin
 * \param[in] direction ray direction, unit length
 * \param[in] t_min,t_max accepted range of the ray parameter
 * \param[out] t ray parameter of the hit (the distance, as direction is unit)
 * \param[out] normal outward unit surface normal at the hit
 * \return true when there is a hit in (t_min, t_max)
 */
bool intersectRay(const ScenePrimitive& primitive, const Eigen::Vector3d& origin,
                  const Eigen::Vector3d& direction, double t_min, double t_max,
                  double& t, Eigen::Vector3d& normal);

/** \brief Euclidean distance from a point to a solid, 0 inside it.
 *
 * Exact for boxes and cylinders; a lower bound for ellipsoids (so a point farther
 * than some clearance by this measure is truly that far).
 * \param[in] primitive the solid
 * \param[in] point query point
 */
double distanceToPrimitive(const ScenePrimitive& primitive,
                           const Eigen::Vector3d& point);

/** \brief Axis-aligned xy bounds of a primitive as (x_min, y_min, x_max, y_max).
 * \param[in] primitive the solid
 */
Eigen::Vector4d footprintBounds(const ScenePrimitive& primitive);

/** \brief Height of the highest point of a primitive. */
double topHeight(const ScenePrimitive& primitive);

/** \brief Reflectivity of the ground (z = 0) at (x, y): gravel and grass around two
 * asphalt roads with dashed center lines, so the ground carries intensity texture.
 * \param[in] x,y world position on the ground
 */
double groundReflectivity(double x, double y);

/** \brief Parameters of the procedural outdoor scene. */
struct SceneParameters {
  /** \brief Seed of the generator; the same parameters give the same scene. */
  unsigned seed = 1;
  /** \brief Side of the square the objects are placed in, meters, centered at the
   * origin. */
  double extent = 120.0;
  /** \brief No object comes closer than this to the z axis, so sensors fit there. */
  double clear_radius = 8.0;
  /** \brief Number of buildings (boxes 5-25 m, about 40% L-shaped). */
  int buildings = 10;
  /** \brief Number of poles (thin tall cylinders, high reflectivity). */
  int poles = 30;
  /** \brief Number of trees (trunk cylinder plus ellipsoid crown). */
  int trees = 25;
  /** \brief Number of bushes (low ellipsoids). */
  int bushes = 20;
  /** \brief Number of parked cars (body and cabin boxes). */
  int cars = 8;
  /** \brief Number of free-standing walls and fences (long thin boxes). */
  int walls = 5;
};

/** \brief Generate the solids of an outdoor scene (the ground plane is implicit).
 *
 * Buildings are spread over angular sectors around the origin so a sensor near the
 * center sees structure in every direction; positions, sizes, yaws and
 * reflectivities are drawn from a std::mt19937 seeded with params.seed, using only
 * its raw output so the scene is identical on every standard library.
 * \param[in] params scene parameters
 * \throws std::invalid_argument for negative counts or a too small extent
 */
std::vector<ScenePrimitive> generateScene(const SceneParameters& params);

/** \brief Counter-based random number: a well mixed 64-bit hash of (seed, index,
 * stream), the same whatever the order or thread in which it is computed.
 * \param[in] seed user seed
 * \param[in] index counter (e.g. ray index)
 * \param[in] stream which of several independent numbers for the same index
 */
std::uint64_t hashRandom(std::uint64_t seed, std::uint64_t index, std::uint64_t stream);

/** \brief Standard normal deviate from hashRandom(seed, index, stream) (Box-Muller).
 * \param[in] seed user seed
 * \param[in] index counter
 * \param[in] stream stream index
 */
double hashGaussian(std::uint64_t seed, std::uint64_t index, std::uint64_t stream);

} // namespace phaser
} // namespace pcl
