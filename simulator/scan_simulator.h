// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
// A small deterministic LiDAR scan simulator: a seeded procedural outdoor scene
// (scene_primitives.h) seen by a spinning multi-beam sensor through exact analytic ray
// casting. Used by `pcl_phaser_align --demo`, the tests and the benchmarks.
#pragma once

#include "scene_primitives.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace pcl {
namespace phaser {

/** \brief Height of the simulated sensor above the ground, meters (a car roof mount).
 */
constexpr double kDefaultSensorHeight = 1.8;

/** \brief Parameters of a spinning multi-beam LiDAR; the defaults resemble a Velodyne
 * HDL-64E (64 beams from -24.8 to +2 degrees) and give about 100k returns per scan.
 *
 * The beams are evenly spaced in elevation; the columns start at azimuth 0 (the
 * sensor's +x axis) and advance counter-clockwise by azimuth_step_deg.
 */
struct LidarParameters {
  /** \brief Number of beams (>= 1); one beam looks at min_elevation_deg. */
  int beams = 64;
  /** \brief Elevation of the lowest beam, degrees. */
  double min_elevation_deg = -24.8;
  /** \brief Elevation of the highest beam, degrees (>= min_elevation_deg). */
  double max_elevation_deg = 2.0;
  /** \brief Horizontal angle between two firings, degrees, in (0, 360]. */
  double azimuth_step_deg = 0.2;
  /** \brief Returns with a measured range below this are dropped, meters. */
  double min_range = 1.0;
  /** \brief Returns with a measured range above this are dropped, meters. */
  double max_range = 100.0;
  /** \brief Standard deviation of the Gaussian range noise, meters (>= 0). */
  double range_noise = 0.02;
  /** \brief Standard deviation of the Gaussian intensity noise (>= 0). */
  double intensity_noise = 0.01;
  /** \brief Seed of the noise; each ray draws its own from (noise_seed, ray index). */
  unsigned noise_seed = 7;
  /** \brief OpenMP threads for the ray casting, 0 for the OpenMP default. The result
   * does not depend on it. */
  int num_threads = 0;
};

/** \brief The nearest surface met by a ray. */
struct RayHit {
  /** \brief Distance from the ray origin to the hit, meters. */
  double range = 0.0;
  /** \brief Hit position, world frame. */
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  /** \brief Outward unit surface normal at the hit, world frame. */
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  /** \brief Reflectivity of the surface at the hit, in [0, 1]. */
  double reflectivity = 0.0;
  /** \brief Index of the hit primitive in SimulatedScene::primitives(), -1 for the
   * ground. */
  int primitive = -1;
};

/** \brief A static scene of solids above an infinite ground plane z = 0, and a LiDAR
 * that scans it.
 *
 * Rays are cast exactly against every surface; a 2-D grid over the solids' footprints
 * keeps a 100k-ray scan in the tens of milliseconds on one core. All queries are
 * const and thread-safe.
 */
class SimulatedScene {
public:
  /** \brief Build the procedural outdoor scene of generateScene(params).
   * \param[in] params scene parameters (seed, extent, object counts)
   */
  explicit SimulatedScene(const SceneParameters& params = SceneParameters());

  /** \brief Build a scene from given solids (e.g. a single box for a test).
   * \param[in] primitives the solids, world frame
   * \param[in] with_ground whether the ground plane z = 0 is part of the scene
   */
  explicit SimulatedScene(std::vector<ScenePrimitive> primitives,
                          bool with_ground = true);

  /** \brief The solids of the scene (the ground plane is implicit). */
  const std::vector<ScenePrimitive>& primitives() const { return primitives_; }

  /** \brief Whether the ground plane z = 0 is part of the scene. */
  bool hasGround() const { return with_ground_; }

  /** \brief Nearest surface along a ray.
   * \param[in] origin ray origin, world frame
   * \param[in] direction ray direction, world frame (normalized internally; nonzero)
   * \param[in] max_range hits beyond this distance are ignored
   * \param[out] hit the nearest hit, when there is one
   * \return true when the ray meets a surface within (0, max_range]
   */
  bool castRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
               double max_range, RayHit& hit) const;

  /** \brief Simulate one full revolution of the LiDAR.
   *
   * Each ray that meets a surface gives one point at the measured range (true
   * distance plus Gaussian noise along the ray) when that range lies in
   * [min_range, max_range]; rays that miss, or whose nearest surface is out of range,
   * give none. The intensity is reflectivity * (0.4 + 0.6 cos(incidence)) plus
   * Gaussian noise, clamped to [0, 1]. Points are ordered by column (azimuth) and,
   * within a column, by beam from the lowest up. The result is bit-identical for the
   * same scene, pose and parameters, whatever the number of threads.
   * \param[in] sensor_pose_in_world pose of the sensor frame in the world (x forward,
   * z up for a level sensor; see makeSensorPose())
   * \param[in] lidar sensor parameters
   * \return the returns in the SENSOR frame; finite, is_dense, width = size, height = 1
   * \throws std::invalid_argument for invalid sensor parameters
   */
  pcl::PointCloud<pcl::PointXYZI>
  scan(const Eigen::Isometry3d& sensor_pose_in_world,
       const LidarParameters& lidar = LidarParameters()) const;

  /** \brief Whether a position is free to put a sensor at: above the ground (when
   * there is one) and at least clearance meters from every solid.
   * \param[in] position world position
   * \param[in] clearance required distance to the solids, meters
   */
  bool isFree(const Eigen::Vector3d& position, double clearance = 1.0) const;

private:
  /** \brief Bin the solids' footprints into the 2-D acceleration grid. */
  void buildGrid();

  /** \brief castRay() for a unit direction. */
  bool castUnitRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                   double max_range, RayHit& hit) const;

  /** \brief The nearest surface found so far along a ray. */
  struct Nearest {
    double t = 0.0; ///< its distance; hits must be strictly closer to replace it
    int id = -2;    ///< primitive index, -1 for the ground, -2 for none yet
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ(); ///< outward unit normal
  };

  /** \brief Replace \a best by the ground plane's hit (when the scene has a ground,
   * the ray is not parallel to it and the hit lies in (kTMin, best.t)). */
  void intersectGround(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                       Nearest& best) const;

  /** \brief Clip a ray's xy projection to the grid: narrows [t_enter, t_leave] to the
   * distances at which it is over the grid.
   * \return false when the ray never is over the grid within the interval (or there
   * is no grid) */
  bool clipToGrid(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                  double& t_enter, double& t_leave) const;

  /** \brief 2-D DDA through the grid cells the ray's xy projection crosses from
   * t_enter on, intersecting their solids; replaces \a best by any closer hit and stops
   * once the next cell lies beyond best.t or t_leave, above or below every solid, or
   * outside the grid. Requires clipToGrid() to have returned true for the interval. */
  void traverseGrid(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                    double t_enter, double t_leave, Nearest& best) const;

  std::vector<ScenePrimitive> primitives_;
  bool with_ground_ = true;
  double cell_size_ = 4.0;
  Eigen::Vector2d grid_min_ = Eigen::Vector2d::Zero();
  int grid_nx_ = 0, grid_ny_ = 0;
  std::vector<int> cell_start_; ///< CSR offsets into cell_items_, grid_nx_*grid_ny_+1
  std::vector<int> cell_items_; ///< primitive indices, cell by cell
  double top_ = 0.0;            ///< highest point of any solid
  double bottom_ = 0.0;         ///< lowest point of any solid
};

/** \brief A sensor pose in the world: position (x, y, height) and orientation
 * Rz(yaw) * Ry(pitch) * Rx(roll).
 * \param[in] x,y position on the ground plane, meters
 * \param[in] yaw heading about z, radians
 * \param[in] roll,pitch tilt about the sensor's x and y axes, radians
 * \param[in] height height of the sensor above the ground, meters
 */
Eigen::Isometry3d makeSensorPose(double x, double y, double yaw, double roll = 0.0,
                                 double pitch = 0.0,
                                 double height = kDefaultSensorHeight);

/** \brief Two scans of the same scene and the exact transform between their frames. */
struct ScanPair {
  /** \brief Scan taken at source_pose, in its own sensor frame. */
  pcl::PointCloud<pcl::PointXYZI> source;
  /** \brief Scan taken at target_pose, in its own sensor frame. */
  pcl::PointCloud<pcl::PointXYZI> target;
  /** \brief Ground truth: p_target = T_target_source * p_source. */
  Eigen::Matrix4d T_target_source = Eigen::Matrix4d::Identity();
  /** \brief Pose of the target sensor in the world. */
  Eigen::Isometry3d target_pose = Eigen::Isometry3d::Identity();
  /** \brief Pose of the source sensor in the world. */
  Eigen::Isometry3d source_pose = Eigen::Isometry3d::Identity();
};

/** \brief Scan a scene from two poses. The target scan uses lidar.noise_seed, the
 * source scan a different seed derived from it, so their noise is independent.
 * \param[in] scene the scene
 * \param[in] target_pose pose of the target sensor in the world
 * \param[in] source_pose pose of the source sensor in the world
 * \param[in] lidar sensor parameters of both scans
 */
ScanPair makeScanPair(const SimulatedScene& scene, const Eigen::Isometry3d& target_pose,
                      const Eigen::Isometry3d& source_pose,
                      const LidarParameters& lidar = LidarParameters());

/** \brief The default registration demo: the outdoor scene of the given seed scanned
 * from a free position near its center (target) and from a second free position 2-4 m
 * away turned by 100-160 degrees of yaw (either way) plus up to 3 degrees of roll and
 * pitch (source).
 * \param[in] seed seed of the scene and of the two poses
 * \param[in] lidar sensor parameters of both scans
 */
ScanPair makeDemoPair(unsigned seed = 1,
                      const LidarParameters& lidar = LidarParameters());

} // namespace phaser
} // namespace pcl
