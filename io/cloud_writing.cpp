/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
// saveCloud(): PCL's PCD and PLY writers, and KITTI .bin.
#include "cloud_reading.h"
#include "io_detail.h"

#include <pcl/common/io.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <vector>

namespace pcl {
namespace phaser {
namespace {

bool writeFile(const std::string& path, std::string_view bytes)
{
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  return (file.write(bytes.data(), static_cast<std::streamsize>(bytes.size())).good());
}

bool saveKittiBin(const std::string& path, const pcl::PCLPointCloud2& cloud)
{
  const std::size_t n = std::size_t{cloud.width} * cloud.height;
  std::vector<float> out(4 * n, 0.0f);
  const char* names[4] = {"x", "y", "z", "intensity"};
  for (int k = 0; k < 4; ++k) {
    const int i = pcl::getFieldIndex(cloud, names[k]);
    for (std::size_t p = 0; i >= 0 && p < n; ++p)
      out[4 * p + k] = static_cast<float>(detail::fieldValue(
          cloud.data.data() + p * cloud.point_step + cloud.fields[i].offset,
          cloud.fields[i].datatype));
  }
  return (writeFile(path, std::string_view(reinterpret_cast<const char*>(out.data()),
                                           out.size() * sizeof(float))));
}

} // namespace

/* PCL 1.13.0's PCDWriter describes the gap between one listed field and the next as a
 * padding field of COUNT (offset - end of the previous field), negative when the fields
 * are not listed in memory order (PointXYZINormal), which no reader accepts. Sorted by
 * offset, the gaps are forward and the data is written unchanged. */
std::string detail::binaryPcd(const pcl::PCLPointCloud2& cloud,
                              const std::string& prefix)
{
  pcl::PCLPointCloud2 layout;
  layout.width = cloud.width;
  layout.height = cloud.height;
  layout.point_step = cloud.point_step;
  layout.fields = cloud.fields;
  std::stable_sort(layout.fields.begin(), layout.fields.end(),
                   [](const auto& a, const auto& b) { return (a.offset < b.offset); });
  return (
      (prefix +
       pcl::PCDWriter().generateHeaderBinary(layout, Eigen::Vector4f::Zero(),
                                             Eigen::Quaternionf::Identity()) +
       "DATA binary\n")
          .append(reinterpret_cast<const char*>(cloud.data.data()), cloud.data.size()));
}

bool saveCloud(const std::string& path, const pcl::PCLPointCloud2& cloud,
               std::string* error)
{
  using namespace detail;
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path parent = fs::path(path).parent_path();
  if (path.empty() || fs::is_directory(path, ec))
    return (fail(error, quoted(path) + ": not a file name (a directory?)"));
  if (!parent.empty() && !fs::is_directory(parent, ec))
    return (fail(error, quoted(path) + ": its directory does not exist"));
  pcl::PCLPointCloud2 checked = cloud;
  if (!checkCloudLayout(checked, path, error))
    return (false);
  if (checked.data.empty())
    return (fail(error, quoted(path) + ": cannot save an empty cloud"));
  try {
    bool ok = false;
    switch (getCloudFormat(path)) {
    case CloudFormat::PCD:
      ok = writeFile(path, binaryPcd(cloud, ""));
      break;
    case CloudFormat::PLY:
      ok = pcl::PLYWriter().write(path, cloud, Eigen::Vector4f::Zero(),
                                  Eigen::Quaternionf::Identity(), true, false) == 0;
      break;
    case CloudFormat::KITTI_BIN:
      ok = saveKittiBin(path, cloud);
      break;
    case CloudFormat::UNKNOWN:
      return (fail(error, unsupportedExtension(path)));
    }
    return (ok || fail(error, quoted(path) + ": cannot write the file"));
  } catch (const std::exception& e) {
    return (fail(error, quoted(path) + ": " + e.what()));
  }
}

} // namespace phaser
} // namespace pcl
