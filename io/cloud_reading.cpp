/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
// loadCloud(): the file checks, the format dispatch, KITTI .bin and the blob checks.
// PCD and PLY are read by PCL in a child (reader_child.cpp).
#include "cloud_reading.h"
#include "io_detail.h"

#include <pcl/common/io.h>

#include <boost/algorithm/string/case_conv.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>

namespace pcl {
namespace phaser {
namespace detail {

namespace fs = std::filesystem;

bool fail(std::string* error, const std::string& message)
{
  if (error)
    *error = message;
  return (false);
}

std::string quoted(const std::string& path)
{
  return ("'" + path + "'");
}

std::string printable(const std::string& text, std::size_t size)
{
  std::string out = text.substr(0, size);
  for (char& c : out)
    c = (c >= 32 && c < 127) ? c : '?';
  return (out);
}

std::string unsupportedExtension(const std::string& path)
{
  const std::string ext = fs::path(path).extension().string();
  return (quoted(path) + ": " +
          (ext.empty() ? std::string("no file extension")
                       : "unsupported extension '" + ext + "'") +
          " (expected .pcd, .ply or .bin)");
}

bool checkInputFile(const std::string& path, std::uintmax_t& size, std::string* error)
{
  if (path.empty())
    return (fail(error, "empty file name"));
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status))
    return (fail(error, quoted(path) + ": no such file"));
  if (fs::is_directory(status))
    return (fail(error, quoted(path) + ": is a directory, not a file"));
  if (!fs::is_regular_file(status))
    return (fail(error, quoted(path) + ": not a regular file"));
  size = fs::file_size(path, ec);
  if (ec || !std::ifstream(path, std::ios::binary).is_open())
    return (fail(error, quoted(path) + ": cannot open for reading"));
  if (size == 0)
    return (fail(error, quoted(path) + ": file is empty (0 bytes)"));
  return (true);
}

double fieldValue(const std::uint8_t* p, std::uint8_t datatype)
{
  double out = 0.0;
  const auto as = [&](auto value) {
    if (pcl::traits::asEnum_v<decltype(value)> == datatype) {
      std::memcpy(&value, p, sizeof(value));
      out = static_cast<double>(value);
    }
  };
  as(std::int8_t{}), as(std::uint8_t{}), as(std::int16_t{}), as(std::uint16_t{});
  as(std::int32_t{}), as(std::uint32_t{}), as(std::int64_t{}), as(std::uint64_t{});
  as(float{}), as(double{});
  return (out);
}

bool checkCloudLayout(pcl::PCLPointCloud2& cloud, const std::string& path,
                      std::string* error)
{
  for (const pcl::PCLPointField& f : cloud.fields) {
    const std::uint64_t size = pcl::getFieldSize(f.datatype);
    if (size == 0 || f.count == 0 || f.offset + f.count * size > cloud.point_step)
      return (fail(error, quoted(path) + ": inconsistent cloud: field '" + f.name +
                              "' does not fit its point"));
  }
  const std::uint64_t points = std::uint64_t{cloud.width} * cloud.height;
  if (cloud.data.size() != points * cloud.point_step)
    return (fail(error, quoted(path) + ": inconsistent cloud: " +
                            std::to_string(cloud.data.size()) + " bytes for " +
                            std::to_string(points) + " points of " +
                            std::to_string(cloud.point_step) + " bytes"));
  cloud.row_step = cloud.width * cloud.point_step;
  const int xyz[3] = {pcl::getFieldIndex(cloud, "x"), pcl::getFieldIndex(cloud, "y"),
                      pcl::getFieldIndex(cloud, "z")};
  if (*std::min_element(xyz, xyz + 3) < 0)
    return (fail(error, quoted(path) + ": the cloud has no x/y/z fields"));
  cloud.is_dense = true;
  for (std::uint64_t i = 0; i < points && cloud.is_dense; ++i)
    for (const int k : xyz)
      cloud.is_dense &= std::isfinite(
          fieldValue(&cloud.data[i * cloud.point_step + cloud.fields[k].offset],
                     cloud.fields[k].datatype));
  return (true);
}

bool checkFloatXYZ(const pcl::PCLPointCloud2& cloud, const std::string& path,
                   std::string* error)
{
  for (const char* axis : {"x", "y", "z"}) {
    const int i = pcl::getFieldIndex(cloud, axis);
    if (i < 0 || cloud.fields[i].datatype != pcl::PCLPointField::FLOAT32 ||
        cloud.fields[i].count != 1)
      return (fail(error, quoted(path) + ": field " + axis +
                              " is not one float32 (load it into a PCLPointCloud2)"));
  }
  return (true);
}

namespace {

/** A KITTI scan: x y z reflectance as little-endian float32 (the host's order). */
bool loadKittiBin(const std::string& path, std::uintmax_t size,
                  pcl::PCLPointCloud2& cloud, std::string* error)
{
  if (size % 16 != 0)
    return (fail(error, quoted(path) + ": not a KITTI .bin scan: its size (" +
                            std::to_string(size) +
                            " bytes) is not a multiple of 16 (4 float32 per point)"));
  if (size > 0xffffffffu) // row_step is 32-bit
    return (fail(error, quoted(path) + ": too many points for one cloud"));
  cloud = pcl::PCLPointCloud2();
  for (const char* name : {"x", "y", "z", "intensity"})
    cloud.fields.push_back({name, static_cast<pcl::uindex_t>(4 * cloud.fields.size()),
                            pcl::PCLPointField::FLOAT32, 1});
  cloud.point_step = 16;
  cloud.width = static_cast<std::uint32_t>(size / 16);
  cloud.height = 1;
  cloud.data.resize(static_cast<std::size_t>(size));
  std::ifstream in(path, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(cloud.data.data()),
               static_cast<std::streamsize>(size)))
    return (fail(error, quoted(path) + ": read error"));
  return (checkCloudLayout(cloud, path, error));
}

} // namespace
} // namespace detail

CloudFormat getCloudFormat(const std::string& path)
{
  const std::string ext =
      boost::algorithm::to_lower_copy(std::filesystem::path(path).extension().string());
  if (ext == ".pcd")
    return (CloudFormat::PCD);
  if (ext == ".ply")
    return (CloudFormat::PLY);
  return (ext == ".bin" ? CloudFormat::KITTI_BIN : CloudFormat::UNKNOWN);
}

bool loadCloud(const std::string& path, pcl::PCLPointCloud2& cloud, std::string* error)
{
  using namespace detail;
  try {
    std::uintmax_t size = 0;
    if (!checkInputFile(path, size, error))
      return (false);
    const CloudFormat format = getCloudFormat(path);
    if (format == CloudFormat::KITTI_BIN)
      return (loadKittiBin(path, size, cloud, error));
    if (format == CloudFormat::UNKNOWN)
      return (fail(error, unsupportedExtension(path)));
    std::string reply;
    if (!readThroughReader(path, reply))
      reply = readInChild(path);
    return (takeReply(path, reply, cloud, error));
  } catch (const std::exception& e) {
    return (fail(error, quoted(path) + ": " + e.what()));
  }
}

} // namespace phaser
} // namespace pcl
