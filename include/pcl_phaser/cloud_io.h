/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace pcl {
namespace phaser {

/** \brief Cloud file formats of loadCloud() and saveCloud(), chosen by extension. */
enum class CloudFormat {
  UNKNOWN,  ///< anything else (no extension, or an unsupported one)
  PCD,      ///< ".pcd": PCL's point cloud data (ascii, binary or binary_compressed)
  PLY,      ///< ".ply": Stanford polygon file (ascii or binary), vertices only
  KITTI_BIN ///< ".bin": KITTI Velodyne scan, float32 quadruples x y z reflectance
};

/** \brief Which fields a cloud carries, for "does this file have xyz/intensity/rgb".
 *
 * Built by getCloudFieldInfo(). PCL's PLY reader already renames nx/ny/nz to
 * normal_x/normal_y/normal_z and packs red/green/blue(/alpha) into rgb (rgba).
 */
struct CloudFieldInfo {
  /** \brief Field names in storage order (empty when the cloud has no fields). */
  std::vector<std::string> names;
  /** \brief The cloud has x, y and z. */
  bool has_xyz = false;
  /** \brief The cloud has "intensity" (KITTI reflectance is loaded under that name). */
  bool has_intensity = false;
  /** \brief The cloud has packed colour, "rgb" or "rgba". */
  bool has_rgb = false;
  /** \brief The cloud has normal_x, normal_y and normal_z. */
  bool has_normals = false;
};

/** \brief Tell the format of a cloud file from its extension (case-insensitive).
 * \param[in] path file name; only its extension is looked at
 * \return the format, or CloudFormat::UNKNOWN
 */
CloudFormat getCloudFormat(const std::string& path);

/** \brief Load a point cloud file into a PCLPointCloud2 blob, choosing the reader by
 * extension: .pcd and .ply through PCL's readers, .bin as a KITTI Velodyne scan
 * (fields x y z intensity, float32, unorganized).
 *
 * Never crashes or aborts on bad input: missing, unreadable or empty files,
 * directories, unknown extensions, garbage content, headers that announce more data
 * than the file holds, a .bin whose size is not a multiple of 16 bytes, and clouds
 * without x/y/z fields all return false with a reason. Before PCL's readers see a
 * .pcd or .ply file its header is checked against the file size (so a lying header
 * cannot trigger a huge allocation) and against the inputs known to crash or abort
 * PCL 1.13's readers (a PCD header without fields; PLY files with more vertices than
 * their obj_info grid, uchar blue before red, an indented obj_info line, or range_grid
 * vertex indices out of range). PCL's readers may still print their own errors.
 *
 * On success the blob is self-consistent (data holds width * height * point_step
 * bytes, row_step = width * point_step) and is_dense is true only when every point
 * has finite x, y and z (PCL's PLY reader reports is_dense = true for range-grid
 * files such as the Stanford bunny scans, which are organized with NaN holes).
 * A well-formed file with zero points loads successfully as an empty cloud.
 *
 * \note PLY files with a range_grid element (Cyberware scans) load as an organized
 * num_cols x num_rows cloud with NaN points where the grid has no vertex, as PCL
 * does. PLY vertex list properties are refused (PCL sizes them from the first vertex
 * only), and so are range_grid ascii bodies that do not hold one element per line.
 * \param[in] path the file to read
 * \param[out] cloud the loaded cloud (unspecified content when false is returned)
 * \param[out] error if not null, receives a human-readable reason on failure
 * \return true on success
 */
bool loadCloud(const std::string& path, pcl::PCLPointCloud2& cloud,
               std::string* error = nullptr);

/** \brief Load a point cloud file into a typed cloud (see the PCLPointCloud2 overload
 * for formats and failure modes), converting with pcl::fromPCLPointCloud2.
 *
 * Fails when the point type has x/y/z but the file stores them as anything other
 * than one float32 each (e.g. a PLY with double vertices); load into a
 * PCLPointCloud2 to handle such files. Other fields of PointT that the file lacks
 * are left at their default values (PCL prints "Failed to find match for field").
 * \param[in] path the file to read
 * \param[out] cloud the loaded cloud (organized clouds keep width and height)
 * \param[out] error if not null, receives a human-readable reason on failure
 * \return true on success
 */
template <typename PointT>
bool loadCloud(const std::string& path, pcl::PointCloud<PointT>& cloud,
               std::string* error = nullptr);

/** \brief Save a cloud, choosing the writer by extension: .pcd writes binary PCD,
 * .ply writes binary little-endian PLY (vertices only, unorganized), .bin writes a
 * KITTI scan (x y z and intensity as float32; intensity 0 when absent).
 * \param[in] path the file to write (its directory must exist)
 * \param[in] cloud a non-empty, self-consistent cloud with x/y/z fields
 * \param[out] error if not null, receives a human-readable reason on failure
 * \return true on success
 */
bool saveCloud(const std::string& path, const pcl::PCLPointCloud2& cloud,
               std::string* error = nullptr);

/** \brief Save a typed cloud (see the PCLPointCloud2 overload).
 * \param[in] path the file to write (.pcd, .ply or .bin)
 * \param[in] cloud the cloud to write
 * \param[out] error if not null, receives a human-readable reason on failure
 * \return true on success
 */
template <typename PointT>
bool saveCloud(const std::string& path, const pcl::PointCloud<PointT>& cloud,
               std::string* error = nullptr);

/** \brief List the fields of a cloud and answer the usual capability questions.
 * Unlike pcl::getFieldsList, safe on a cloud without fields.
 * \param[in] cloud the cloud to inspect
 * \return the field names and has_xyz / has_intensity / has_rgb / has_normals
 */
CloudFieldInfo getCloudFieldInfo(const pcl::PCLPointCloud2& cloud);

/** \brief Whether a cloud has a field of the given name.
 * \param[in] cloud the cloud to inspect
 * \param[in] name the field name, e.g. "intensity"
 * \return true if a field of that name exists
 */
bool hasField(const pcl::PCLPointCloud2& cloud, const std::string& name);

/** \brief Parse a rigid transform from text: 16 numbers (row-major 4x4) or 12 numbers
 * (row-major 3x4, the last row is then 0 0 0 1), separated by whitespace; '#' starts a
 * comment that runs to the end of the line.
 *
 * The rotation block R must be orthonormal (max |R^T R - I| <= tolerance) with
 * det(R) > 0, and a given last row must be 0 0 0 1 within tolerance. The parsed
 * numbers are returned unchanged (no re-orthonormalization).
 * \param[in] text the numbers
 * \param[out] transform the parsed transform (unchanged on failure)
 * \param[out] error if not null, receives a human-readable reason on failure
 * \param[in] tolerance the orthonormality tolerance, finite and >= 0
 * \return true on success
 */
bool parseTransform(const std::string& text, Eigen::Matrix4d& transform,
                    std::string* error = nullptr, double tolerance = 1e-4);

/** \brief Load a rigid transform from a text file (format and checks as in
 * parseTransform()), e.g. the T_*.txt and relative.txt files of the shared data.
 * \param[in] path the file to read
 * \param[out] transform the loaded transform (unchanged on failure)
 * \param[out] error if not null, receives a human-readable reason on failure
 * \param[in] tolerance the orthonormality tolerance, finite and >= 0
 * \return true on success
 */
bool loadTransform(const std::string& path, Eigen::Matrix4d& transform,
                   std::string* error = nullptr, double tolerance = 1e-4);

/** \brief Write a transform as 4 lines of 4 numbers (shortest round-trip decimal
 * form, so loadTransform() reads back the identical matrix).
 * \param[in] path the file to write
 * \param[in] transform the transform; no validation is done
 * \param[out] error if not null, receives a human-readable reason on failure
 * \return true on success
 */
bool saveTransform(const std::string& path, const Eigen::Matrix4d& transform,
                   std::string* error = nullptr);

namespace detail {

/** \brief Check that the x, y and z fields of a loaded cloud are one float32 each, as
 * the xyz point types expect; used by the typed loadCloud().
 * \param[in] cloud the loaded cloud
 * \param[in] path the file name, for the message
 * \param[out] error if not null, receives a human-readable reason on failure
 * \return true if x, y and z are float32 with count 1
 */
bool checkFloatXYZ(const pcl::PCLPointCloud2& cloud, const std::string& path,
                   std::string* error);

} // namespace detail

template <typename PointT>
bool loadCloud(const std::string& path, pcl::PointCloud<PointT>& cloud,
               std::string* error)
{
  pcl::PCLPointCloud2 blob;
  if (!loadCloud(path, blob, error))
    return (false);
  if constexpr (pcl::traits::has_xyz_v<PointT>) {
    if (!detail::checkFloatXYZ(blob, path, error))
      return (false);
  }
  if (blob.data.empty()) {
    // fromPCLPointCloud2 takes &data[0], which an empty vector does not have.
    cloud.clear();
    cloud.header = blob.header;
    cloud.width = blob.width;
    cloud.height = blob.height;
    cloud.is_dense = true;
    return (true);
  }
  pcl::fromPCLPointCloud2(blob, cloud);
  return (true);
}

template <typename PointT>
bool saveCloud(const std::string& path, const pcl::PointCloud<PointT>& cloud,
               std::string* error)
{
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(cloud, blob);
  return (saveCloud(path, blob, error));
}

} // namespace phaser
} // namespace pcl
