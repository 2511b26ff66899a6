/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
/** \file cloud_reading.h
 * \brief Cloud files for the tools, bench/ and the tests (not installed): PCL's readers
 * made safe on hostile files, the KITTI .bin format and PCL's writers. */
#pragma once

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <string>
#include <sys/types.h>

namespace pcl {
namespace phaser {

/** \brief Cloud file formats, chosen by extension. */
enum class CloudFormat {
  UNKNOWN,  ///< anything else (no extension, or an unsupported one)
  PCD,      ///< ".pcd": PCL's point cloud data (ascii, binary or binary_compressed)
  PLY,      ///< ".ply": Stanford polygon file (ascii or binary), vertices only
  KITTI_BIN ///< ".bin": KITTI Velodyne scan, float32 quadruples x y z reflectance
};

/** \brief The format of a cloud file from its extension (case-insensitive).
 * \param[in] path file name; only its extension is looked at
 * \return the format, or CloudFormat::UNKNOWN
 */
CloudFormat getCloudFormat(const std::string& path);

/** \brief Load a cloud file into a blob: .pcd and .ply through PCL's readers, .bin as a
 * KITTI Velodyne scan (fields x y z intensity, float32, unorganized).
 *
 * Never crashes, aborts or hangs on bad input: PCL's reader runs in a forked child
 * process with a memory and time limit. Missing, unreadable, empty or non-regular
 * files, unknown extensions, clouds PCL rejects, clouds without x/y/z fields and a .bin
 * whose size is not a multiple of 16 bytes fail with a reason that names the file.
 * PCL's readers may print their own errors.
 *
 * On success the blob is self-consistent (data holds width * height * point_step bytes,
 * row_step = width * point_step, every field inside point_step) and is_dense is true
 * only when every float x/y/z is finite. A well-formed file with zero points loads as
 * an empty cloud.
 * \param[in] path the file to read
 * \param[out] cloud the loaded cloud (unspecified content when false is returned)
 * \param[out] error if not null, receives a human-readable reason on failure
 * \return true on success
 */
bool loadCloud(const std::string& path, pcl::PCLPointCloud2& cloud,
               std::string* error = nullptr);

/** \brief Load a cloud file into a typed cloud (formats and failures as for the blob
 * overload), converting with pcl::fromPCLPointCloud2. Fails when PointT has x/y/z but
 * the file stores them as anything other than one float32 each.
 * \param[in] path the file to read
 * \param[out] cloud the loaded cloud (organized clouds keep width and height)
 * \param[out] error if not null, receives a human-readable reason on failure
 * \return true on success
 */
template <typename PointT>
bool loadCloud(const std::string& path, pcl::PointCloud<PointT>& cloud,
               std::string* error = nullptr);

/** \brief Start a small process that reads the .pcd and .ply files of loadCloud(), each
 * in a child of its own, so that a program holding hundreds of megabytes of working
 * memory (pcl_phaser_batch) never forks (copy-on-write: about 22k page faults and 10 %
 * of the wall time per revisit pair in the batch). Without it, or if it dies,
 * loadCloud() forks from the caller. Call it from the main thread before any other
 * thread starts (the reader dies with the thread that forked it); idempotent.
 * \return false if it could not start
 */
bool startCloudReader();

/** \brief The reader process of startCloudReader(), or -1 when none runs. */
pid_t cloudReaderPid();

/** \brief Save a cloud, the writer chosen by extension: .pcd binary PCD, .ply binary
 * PLY (vertices only, unorganized), .bin a KITTI scan (x y z intensity as float32,
 * intensity 0 when absent).
 * \param[in] path the file to write (its directory must exist)
 * \param[in] cloud a non-empty, self-consistent cloud with x/y/z fields
 * \param[out] error if not null, receives a human-readable reason on failure
 * \return true on success
 */
bool saveCloud(const std::string& path, const pcl::PCLPointCloud2& cloud,
               std::string* error = nullptr);

/** \brief Save a typed cloud (see the blob overload).
 * \param[in] path the file to write (.pcd, .ply or .bin)
 * \param[in] cloud the cloud to write
 * \param[out] error if not null, receives a human-readable reason on failure
 * \return true on success
 */
template <typename PointT>
bool saveCloud(const std::string& path, const pcl::PointCloud<PointT>& cloud,
               std::string* error = nullptr)
{
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(cloud, blob);
  return (saveCloud(path, blob, error));
}

namespace detail {

/** \brief Whether x, y and z are one float32 each, as the xyz point types expect; if
 * not, a reason naming \a path in \a error (when not null). */
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
  cloud.clear();
  cloud.header = blob.header;
  cloud.is_dense = true;
  if (!blob.data.empty()) // fromPCLPointCloud2 takes &data[0]
    pcl::fromPCLPointCloud2(blob, cloud);
  return (true);
}

} // namespace phaser
} // namespace pcl
