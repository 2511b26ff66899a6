/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * What the tests of io/cloud_reading.h share: a temporary directory, a PCL console
 * silencer, file helpers, sample headers and clouds.
 */
#pragma once

#include "../registration/test_data.h"
#include "cloud_reading.h"
#include "transform_file.h"

#include <pcl/common/io.h>
#include <pcl/console/print.h>
#include <pcl/filters/filter.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

namespace fs = std::filesystem;
using pcl::phaser::CloudFormat;
using pcl::phaser::getCloudFormat;
using pcl::phaser::loadCloud;
using pcl::phaser::loadTransform;
using pcl::phaser::parseTransform;
using pcl::phaser::saveCloud;
using pcl::phaser::test::dataPath;

namespace pcl::phaser {
namespace test {

/** A fresh directory under the system temp dir, removed with its content. */
class TempDir {
public:
  TempDir()
  {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::random_device rd;
    const std::string name = std::string("pcl_phaser_cloud_reading_") +
                             (info ? info->name() : "x") + "_" + std::to_string(rd()) +
                             std::to_string(rd());
    path_ = fs::temp_directory_path() / name;
    fs::create_directories(path_);
  }
  ~TempDir()
  {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string file(const std::string& name) const { return ((path_ / name).string()); }

private:
  fs::path path_;
};

/** Silences PCL's console output (readers complain loudly about garbage). */
class QuietPcl {
public:
  QuietPcl()
      : level_(pcl::console::getVerbosityLevel())
  {
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  }
  ~QuietPcl() { pcl::console::setVerbosityLevel(level_); }
  QuietPcl(const QuietPcl&) = delete;
  QuietPcl& operator=(const QuietPcl&) = delete;

private:
  pcl::console::VERBOSITY_LEVEL level_;
};

inline bool hasField(const pcl::PCLPointCloud2& cloud, const std::string& name)
{
  return (pcl::getFieldIndex(cloud, name) >= 0);
}

inline bool hasXYZ(const pcl::PCLPointCloud2& cloud)
{
  return (hasField(cloud, "x") && hasField(cloud, "y") && hasField(cloud, "z"));
}

inline std::vector<std::string> fieldNames(const pcl::PCLPointCloud2& cloud)
{
  std::vector<std::string> names;
  for (const pcl::PCLPointField& f : cloud.fields)
    names.push_back(f.name);
  return (names);
}

inline void writeFile(const std::string& path, const std::string& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << path;
}

inline std::string readFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return (std::string(std::istreambuf_iterator<char>(in), {}));
}

inline std::string randomBytes(std::size_t n, std::uint32_t seed)
{
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  std::string s(n, '\0');
  for (char& c : s)
    c = static_cast<char>(byte(rng));
  return (s);
}

template <typename T>
inline std::string bytesOf(const std::vector<T>& values)
{
  return (std::string(reinterpret_cast<const char*>(values.data()),
                      values.size() * sizeof(T)));
}

inline std::size_t countFinite(const pcl::PointCloud<pcl::PointXYZ>& cloud)
{
  return (static_cast<std::size_t>(
      std::count_if(cloud.begin(), cloud.end(), [](const pcl::PointXYZ& p) {
        return (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
      })));
}

/** What every successful load must give: a self-consistent blob with x/y/z. */
inline void expectConsistent(const pcl::PCLPointCloud2& blob, const std::string& what)
{
  EXPECT_EQ(blob.data.size(),
            static_cast<std::size_t>(blob.width) * blob.height * blob.point_step)
      << what;
  EXPECT_EQ(blob.row_step, blob.width * blob.point_step) << what;
  EXPECT_TRUE(hasXYZ(blob)) << what;
}

/** Load, and check the outcome is either a clean failure or a consistent cloud (the
 *  typed load only after a successful one: it fails exactly when the blob load does).
 */
inline void loadAndCheckInvariants(const std::string& path, const std::string& what)
{
  pcl::PCLPointCloud2 blob;
  std::string error;
  if (!loadCloud(path, blob, &error)) {
    EXPECT_FALSE(error.empty()) << what;
    return;
  }
  expectConsistent(blob, what);
  pcl::PointCloud<pcl::PointXYZ> cloud;
  error.clear();
  if (loadCloud(path, cloud, &error)) {
    EXPECT_EQ(cloud.size(), static_cast<std::size_t>(cloud.width) * cloud.height)
        << what;
  } else {
    EXPECT_FALSE(error.empty()) << what;
  }
}

inline std::string pcdHeader(const std::string& fields, const std::string& size,
                             const std::string& type, const std::string& count,
                             const std::string& width, const std::string& height,
                             const std::string& points, const std::string& data)
{
  return ("# .PCD v0.7\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " + size + "\nTYPE " +
          type + "\nCOUNT " + count + "\nWIDTH " + width + "\nHEIGHT " + height +
          "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + points + "\nDATA " + data + "\n");
}

inline std::string xyzPcdHeader(const std::string& points, const std::string& data)
{
  return (pcdHeader("x y z", "4 4 4", "F F F", "1 1 1", points, "1", points, data));
}

/** A PLY header with float x/y/z vertices: before goes ahead of the vertex element
 *  (obj_info lines), after follows its properties (more properties or elements). */
inline std::string plyXYZ(const std::string& format, const std::string& vertices,
                          const std::string& before = "", const std::string& after = "")
{
  return ("ply\nformat " + format + " 1.0\n" + before + "element vertex " + vertices +
          "\nproperty float x\nproperty float y\nproperty float z\n" + after +
          "end_header\n");
}

inline std::string gridInfo(const std::string& cols, const std::string& rows)
{
  return ("obj_info num_cols " + cols + "\nobj_info num_rows " + rows + "\n");
}

inline std::string rangeGrid(const std::string& cells)
{
  return ("element range_grid " + cells + "\nproperty list uchar int vertex_indices\n");
}

/** A small XYZI test cloud with varied values. */
inline pcl::PointCloud<pcl::PointXYZI> makeCloud(std::size_t n, std::uint32_t seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-20.0f, 20.0f);
  pcl::PointCloud<pcl::PointXYZI> cloud;
  for (std::size_t i = 0; i < n; ++i) {
    pcl::PointXYZI p;
    p.x = u(rng);
    p.y = u(rng);
    p.z = u(rng);
    p.intensity = (u(rng) + 20.0f) / 40.0f;
    cloud.push_back(p);
  }
  return (cloud);
}

inline void expectSameXYZI(const pcl::PointCloud<pcl::PointXYZI>& a,
                           const pcl::PointCloud<pcl::PointXYZI>& b,
                           bool compare_intensity = true)
{
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].x, b[i].x) << i;
    EXPECT_EQ(a[i].y, b[i].y) << i;
    EXPECT_EQ(a[i].z, b[i].z) << i;
    if (compare_intensity) {
      EXPECT_EQ(a[i].intensity, b[i].intensity) << i;
    }
  }
}

inline double rotationAngleDeg(const Eigen::Matrix4d& t)
{
  const double c = std::clamp((t.topLeftCorner<3, 3>().trace() - 1.0) / 2.0, -1.0, 1.0);
  return (std::acos(c) * 180.0 / M_PI);
}

} // namespace test
} // namespace pcl::phaser
