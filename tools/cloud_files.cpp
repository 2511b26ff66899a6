/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
// cloud_reading.h: format dispatch, file checks, the blob checks, KITTI .bin, the
// writers, and the transform text format. PCD and PLY reading is cloud_reading.cpp.
#include "cloud_reading.h"

#include <pcl/common/io.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

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

/** At most 40 characters of text, non-printable ones as '?'. */
std::string excerpt(const std::string& text)
{
  std::string out = text.substr(0, 40);
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

bool loadWithPcl(const std::string& path, CloudFormat format, std::uintmax_t file_size,
                 pcl::PCLPointCloud2& cloud, std::string* error);
bool loadThroughReader(const std::string& path, CloudFormat format,
                       std::uintmax_t file_size, pcl::PCLPointCloud2& cloud,
                       std::string* error, bool& used);

/** A readable, non-empty regular file, and its size. */
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

/** The blob invariants of loadCloud(), is_dense recomputed (PCL's PLY reader reports
 * dense range-grid clouds that have NaN holes), and x/y/z present. */
bool checkCloudLayout(pcl::PCLPointCloud2& cloud, const std::string& path,
                      std::string* error)
{
  for (const pcl::PCLPointField& f : cloud.fields) {
    const std::uint64_t end =
        f.offset + std::uint64_t{f.count} * pcl::getFieldSize(f.datatype);
    if (pcl::getFieldSize(f.datatype) == 0 || f.count == 0 || end > cloud.point_step)
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
  int xyz[3];
  for (int k = 0; k < 3; ++k)
    if ((xyz[k] =
             pcl::getFieldIndex(cloud, std::string(1, static_cast<char>('x' + k)))) < 0)
      return (fail(error, quoted(path) + ": the cloud has no x/y/z fields"));
  cloud.is_dense = true;
  for (std::uint64_t i = 0; i < points && cloud.is_dense; ++i)
    for (const int k : xyz) {
      const pcl::PCLPointField& f = cloud.fields[k];
      const std::uint8_t* p = cloud.data.data() + i * cloud.point_step + f.offset;
      double v = 0.0;
      if (f.datatype == pcl::PCLPointField::FLOAT32) {
        float x;
        std::memcpy(&x, p, sizeof(x));
        v = x;
      } else if (f.datatype == pcl::PCLPointField::FLOAT64)
        std::memcpy(&v, p, sizeof(v));
      cloud.is_dense = cloud.is_dense && std::isfinite(v);
    }
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

/** Bytes of one KITTI record: x y z reflectance as little-endian float32. */
constexpr std::uintmax_t kKittiRecord = 16;

bool loadKittiBin(const std::string& path, std::uintmax_t size,
                  pcl::PCLPointCloud2& cloud, std::string* error)
{
  if (size % kKittiRecord != 0)
    return (fail(error, quoted(path) + ": not a KITTI .bin scan: its size (" +
                            std::to_string(size) +
                            " bytes) is not a multiple of 16 (4 float32 per point)"));
  if (size > 0xffffffffu) // row_step is 32-bit
    return (fail(error, quoted(path) + ": too many points for one cloud"));
  cloud = pcl::PCLPointCloud2();
  const char* names[4] = {"x", "y", "z", "intensity"};
  for (std::uint32_t k = 0; k < 4; ++k) {
    pcl::PCLPointField f;
    f.name = names[k];
    f.offset = 4 * k;
    f.datatype = pcl::PCLPointField::FLOAT32;
    f.count = 1;
    cloud.fields.push_back(f);
  }
  cloud.point_step = kKittiRecord;
  cloud.width = static_cast<std::uint32_t>(size / kKittiRecord);
  cloud.height = 1;
  cloud.data.resize(static_cast<std::size_t>(size));
  std::ifstream in(path, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(cloud.data.data()),
               static_cast<std::streamsize>(size)))
    return (fail(error, quoted(path) + ": read error"));
  return (checkCloudLayout(cloud, path, error)); // a little-endian host is assumed
}

/** One value of a field as float (any PCL datatype). */
float readAsFloat(const std::uint8_t* p, std::uint8_t datatype)
{
  const auto as = [p](auto value) {
    std::memcpy(&value, p, sizeof(value));
    return (static_cast<float>(value));
  };
  switch (datatype) {
  case pcl::PCLPointField::INT8:
    return (as(std::int8_t{}));
  case pcl::PCLPointField::UINT8:
    return (as(std::uint8_t{}));
  case pcl::PCLPointField::INT16:
    return (as(std::int16_t{}));
  case pcl::PCLPointField::UINT16:
    return (as(std::uint16_t{}));
  case pcl::PCLPointField::INT32:
    return (as(std::int32_t{}));
  case pcl::PCLPointField::UINT32:
    return (as(std::uint32_t{}));
  case pcl::PCLPointField::FLOAT64:
    return (as(double{}));
  default:
    return (as(float{}));
  }
}

bool saveKittiBin(const std::string& path, const pcl::PCLPointCloud2& cloud)
{
  const std::size_t n = std::size_t{cloud.width} * cloud.height;
  std::vector<float> out(4 * n, 0.0f);
  const char* names[4] = {"x", "y", "z", "intensity"};
  for (int k = 0; k < 4; ++k) {
    const int i = pcl::getFieldIndex(cloud, names[k]);
    for (std::size_t p = 0; i >= 0 && p < n; ++p)
      out[4 * p + k] =
          readAsFloat(cloud.data.data() + p * cloud.point_step + cloud.fields[i].offset,
                      cloud.fields[i].datatype);
  }
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(reinterpret_cast<const char*>(out.data()),
             static_cast<std::streamsize>(out.size() * sizeof(float)));
  return (file.good());
}

/** PCL 1.13.0's PCDWriter describes the gap between one listed field and the next as
 * a padding field of COUNT (offset - end of the previous field): a type whose fields
 * are not listed in memory order (PointXYZINormal lists intensity before normal_x and
 * stores it after) gets a negative COUNT that no reader accepts. In offset order the
 * gaps are forward and the data is written unchanged. */
bool savePcd(const std::string& path, const pcl::PCLPointCloud2& cloud)
{
  pcl::PCLPointCloud2 sorted = cloud;
  std::stable_sort(sorted.fields.begin(), sorted.fields.end(),
                   [](const auto& a, const auto& b) { return (a.offset < b.offset); });
  return (pcl::PCDWriter().writeBinary(path, sorted) == 0);
}

} // namespace
} // namespace detail

using namespace detail;

CloudFormat getCloudFormat(const std::string& path)
{
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return (static_cast<char>(std::tolower(c))); });
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
  try {
    std::uintmax_t size = 0;
    if (!checkInputFile(path, size, error))
      return (false);
    switch (getCloudFormat(path)) {
    case CloudFormat::KITTI_BIN:
      return (loadKittiBin(path, size, cloud, error));
    case CloudFormat::PCD:
    case CloudFormat::PLY: {
      bool used = false;
      const bool ok =
          loadThroughReader(path, getCloudFormat(path), size, cloud, error, used);
      return (used ? ok : loadWithPcl(path, getCloudFormat(path), size, cloud, error));
    }
    case CloudFormat::UNKNOWN:
      break;
    }
    return (fail(error, unsupportedExtension(path)));
  } catch (const std::exception& e) {
    return (fail(error, quoted(path) + ": " + e.what()));
  }
}

bool saveCloud(const std::string& path, const pcl::PCLPointCloud2& cloud,
               std::string* error)
{
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
      ok = savePcd(path, cloud);
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

bool parseTransform(const std::string& text, Eigen::Matrix4d& transform,
                    std::string* error, double tolerance)
{
  if (!std::isfinite(tolerance) || tolerance < 0.0)
    return (fail(error, "tolerance must be finite and >= 0"));
  std::vector<double> values;
  std::istringstream lines(text);
  std::string line, token;
  while (std::getline(lines, line)) {
    std::istringstream tokens(line.substr(0, line.find('#')));
    while (tokens >> token) {
      const char* begin = token.data() + (token[0] == '+' ? 1 : 0);
      const char* end = token.data() + token.size();
      double v = 0.0;
      const auto r = std::from_chars(begin, end, v);
      if (r.ec != std::errc() || r.ptr != end)
        return (fail(error, "'" + excerpt(token) + "' is not a number"));
      if (!std::isfinite(v))
        return (fail(error, "non-finite value '" + excerpt(token) + "'"));
      values.push_back(v);
    }
  }
  if (values.size() != 12 && values.size() != 16)
    return (fail(error, "expected 12 (3x4) or 16 (4x4) numbers, found " +
                            std::to_string(values.size())));
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  for (std::size_t i = 0; i < values.size(); ++i)
    m(static_cast<Eigen::Index>(i / 4), static_cast<Eigen::Index>(i % 4)) = values[i];
  const Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
  const double deviation =
      (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  char why[160] = "";
  if (!((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() <= tolerance))
    std::snprintf(why, sizeof(why), "the last row is not 0 0 0 1");
  else if (!(deviation <= tolerance))
    std::snprintf(
        why, sizeof(why),
        "the rotation block is not orthonormal: max |R^T R - I| = %.3g > %.3g",
        deviation, tolerance);
  else if (!(r.determinant() > 0.0))
    std::snprintf(why, sizeof(why),
                  "the rotation block has determinant %.3g (a "
                  "reflection, not a rotation)",
                  r.determinant());
  if (why[0] != '\0')
    return (fail(error, why));
  transform = m;
  return (true);
}

bool loadTransform(const std::string& path, Eigen::Matrix4d& transform,
                   std::string* error, double tolerance)
{
  std::uintmax_t size = 0;
  if (!checkInputFile(path, size, error))
    return (false);
  if (size > (1u << 20))
    return (fail(error, quoted(path) + ": too large for a transform file"));
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  std::string why;
  if (!parseTransform(text, transform, &why, tolerance))
    return (fail(error, quoted(path) + ": " + why));
  return (true);
}

} // namespace phaser
} // namespace pcl
