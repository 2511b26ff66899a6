/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
// The entry points of <pcl_phaser/cloud_io.h> for clouds: format dispatch, the
// exception guards, and field queries. The formats live in cloud_io_pcd.cpp,
// cloud_io_ply.cpp (+ cloud_io_ply_range_grid.cpp) and cloud_io_kitti.cpp, shared
// helpers in cloud_io_common.cpp, transforms in cloud_io_transform.cpp.
#include "cloud_io_detail.h"

#include <pcl_phaser/cloud_io.h>

#include <pcl/common/io.h>

#include <exception>
#include <filesystem>
#include <new>
#include <string>

namespace pcl {
namespace phaser {

using namespace io_detail;

namespace {

namespace fs = std::filesystem;

bool loadCloudUnguarded(const std::string& path, pcl::PCLPointCloud2& cloud,
                        std::string* error)
{
  std::uintmax_t size = 0;
  if (!checkInputFile(path, size, error))
    return (false);
  switch (getCloudFormat(path)) {
  case CloudFormat::KITTI_BIN:
    return (loadKittiBin(path, size, cloud, error));
  case CloudFormat::PCD:
    return (loadPcd(path, size, cloud, error));
  case CloudFormat::PLY:
    return (loadPly(path, size, cloud, error));
  case CloudFormat::UNKNOWN:
    break;
  }
  return (fail(error, unsupportedExtensionMessage(path)));
}

bool saveCloudUnguarded(const std::string& path, const pcl::PCLPointCloud2& cloud,
                        std::string* error)
{
  if (path.empty())
    return (fail(error, "empty file name"));
  const CloudFormat format = getCloudFormat(path);
  if (format == CloudFormat::UNKNOWN)
    return (fail(error, unsupportedExtensionMessage(path)));
  std::error_code ec;
  if (fs::is_directory(path, ec))
    return (fail(error, quoted(path) + ": is a directory"));
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent, ec))
    return (fail(error, quoted(path) + ": directory " + quoted(parent.string()) +
                            " does not exist"));
  std::string why;
  if (!checkBlobLayout(cloud, why))
    return (fail(error, quoted(path) + ": cannot save: " + why));
  if (cloud.width * static_cast<std::uint64_t>(cloud.height) == 0)
    return (fail(error, quoted(path) + ": cannot save an empty cloud"));
  if (!hasXYZFields(cloud))
    return (fail(error, quoted(path) + ": cannot save: the cloud has no x/y/z fields " +
                            "(fields: " + fieldList(cloud) + ")"));
  switch (format) {
  case CloudFormat::PCD:
    return (savePcd(path, cloud, error));
  case CloudFormat::PLY:
    return (savePly(path, cloud, error));
  case CloudFormat::KITTI_BIN:
    return (saveKittiBin(path, cloud, error));
  case CloudFormat::UNKNOWN:
    break;
  }
  return (fail(error, quoted(path) + ": unsupported format"));
}

/** Run io(), turning exceptions into "'path': <noun> error: ..." failures. */
template <typename Io>
bool guarded(const std::string& path, const char* noun, const char* gerund,
             std::string* error, Io io)
{
  const std::string prefix = quoted(path) + ": ";
  try {
    return (io());
  } catch (const std::bad_alloc&) {
    return (fail(error, prefix + "out of memory while " + gerund));
  } catch (const std::exception& e) {
    return (fail(error, prefix + noun + " error: " + excerpt(e.what(), 200)));
  } catch (...) {
    return (fail(error, prefix + noun + " error (unknown exception)"));
  }
}

} // namespace

CloudFormat getCloudFormat(const std::string& path)
{
  const std::string ext = lowerExtension(path);
  if (ext == ".pcd")
    return (CloudFormat::PCD);
  if (ext == ".ply")
    return (CloudFormat::PLY);
  if (ext == ".bin")
    return (CloudFormat::KITTI_BIN);
  return (CloudFormat::UNKNOWN);
}

bool loadCloud(const std::string& path, pcl::PCLPointCloud2& cloud, std::string* error)
{
  return (guarded(path, "read", "reading", error,
                  [&] { return (loadCloudUnguarded(path, cloud, error)); }));
}

bool saveCloud(const std::string& path, const pcl::PCLPointCloud2& cloud,
               std::string* error)
{
  return (guarded(path, "write", "writing", error,
                  [&] { return (saveCloudUnguarded(path, cloud, error)); }));
}

CloudFieldInfo getCloudFieldInfo(const pcl::PCLPointCloud2& cloud)
{
  CloudFieldInfo info;
  for (const auto& f : cloud.fields)
    info.names.push_back(f.name);
  const auto has = [&](const char* name) { return (hasField(cloud, name)); };
  info.has_xyz = has("x") && has("y") && has("z");
  info.has_intensity = has("intensity");
  info.has_rgb = has("rgb") || has("rgba");
  info.has_normals = has("normal_x") && has("normal_y") && has("normal_z");
  return (info);
}

bool hasField(const pcl::PCLPointCloud2& cloud, const std::string& name)
{
  const pcl::PCLPointField* f = nullptr;
  return (findField(cloud, name, f));
}

namespace detail {

bool checkFloatXYZ(const pcl::PCLPointCloud2& cloud, const std::string& path,
                   std::string* error)
{
  for (const char* name : {"x", "y", "z"}) {
    const pcl::PCLPointField* f = nullptr;
    if (!findField(cloud, name, f))
      return (fail(error, quoted(path) + ": the cloud has no '" + name + "' field"));
    if (f->datatype != pcl::PCLPointField::FLOAT32 || f->count != 1)
      return (fail(error, quoted(path) + ": field '" + name + "' is stored as " +
                              std::to_string(f->count) + " x " +
                              std::to_string(pcl::getFieldSize(f->datatype) * 8) +
                              "-bit " +
                              (f->datatype == pcl::PCLPointField::FLOAT32 ||
                                       f->datatype == pcl::PCLPointField::FLOAT64
                                   ? "float"
                                   : "integer") +
                              ", but the point type needs one float32; load into a "
                              "pcl::PCLPointCloud2 and convert instead"));
  }
  return (true);
}

} // namespace detail
} // namespace phaser
} // namespace pcl
