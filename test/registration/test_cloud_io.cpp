/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "test_data.h"

#include <pcl_phaser/cloud_io.h>

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
using pcl::phaser::CloudFieldInfo;
using pcl::phaser::CloudFormat;
using pcl::phaser::getCloudFieldInfo;
using pcl::phaser::getCloudFormat;
using pcl::phaser::hasField;
using pcl::phaser::loadCloud;
using pcl::phaser::loadTransform;
using pcl::phaser::parseTransform;
using pcl::phaser::saveCloud;
using pcl::phaser::saveTransform;
using pcl_phaser::test::dataPath;

namespace {

/** A fresh directory under the system temp dir, removed with its content. */
class TempDir {
public:
  TempDir()
  {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::random_device rd;
    const std::string name = std::string("pcl_phaser_cloud_io_") +
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

void writeFile(const std::string& path, const std::string& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << path;
}

std::string readFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return (std::string(std::istreambuf_iterator<char>(in), {}));
}

std::string randomBytes(std::size_t n, std::uint32_t seed)
{
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  std::string s(n, '\0');
  for (char& c : s)
    c = static_cast<char>(byte(rng));
  return (s);
}

template <typename T>
std::string bytesOf(const std::vector<T>& values)
{
  return (std::string(reinterpret_cast<const char*>(values.data()),
                      values.size() * sizeof(T)));
}

std::size_t countFinite(const pcl::PointCloud<pcl::PointXYZ>& cloud)
{
  return (static_cast<std::size_t>(
      std::count_if(cloud.begin(), cloud.end(), [](const pcl::PointXYZ& p) {
        return (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
      })));
}

/** What every successful load must give: a self-consistent blob with x/y/z. */
void expectConsistent(const pcl::PCLPointCloud2& blob, const std::string& what)
{
  EXPECT_EQ(blob.data.size(),
            static_cast<std::size_t>(blob.width) * blob.height * blob.point_step)
      << what;
  EXPECT_EQ(blob.row_step, blob.width * blob.point_step) << what;
  EXPECT_TRUE(getCloudFieldInfo(blob).has_xyz) << what;
}

/** Load, and check the outcome is either a clean failure or a consistent cloud. */
void loadAndCheckInvariants(const std::string& path, const std::string& what)
{
  pcl::PCLPointCloud2 blob;
  std::string error;
  if (loadCloud(path, blob, &error)) {
    expectConsistent(blob, what);
  } else {
    EXPECT_FALSE(error.empty()) << what;
  }
  pcl::PointCloud<pcl::PointXYZ> cloud;
  error.clear();
  if (loadCloud(path, cloud, &error)) {
    EXPECT_EQ(cloud.size(), static_cast<std::size_t>(cloud.width) * cloud.height)
        << what;
  } else {
    EXPECT_FALSE(error.empty()) << what;
  }
}

std::string pcdHeader(const std::string& fields, const std::string& size,
                      const std::string& type, const std::string& count,
                      const std::string& width, const std::string& height,
                      const std::string& points, const std::string& data)
{
  return ("# .PCD v0.7\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " + size + "\nTYPE " +
          type + "\nCOUNT " + count + "\nWIDTH " + width + "\nHEIGHT " + height +
          "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + points + "\nDATA " + data + "\n");
}

std::string xyzPcdHeader(const std::string& points, const std::string& data)
{
  return (pcdHeader("x y z", "4 4 4", "F F F", "1 1 1", points, "1", points, data));
}

/** A PLY header with float x/y/z vertices: before goes ahead of the vertex element
 *  (obj_info lines), after follows its properties (more properties or elements). */
std::string plyXYZ(const std::string& format, const std::string& vertices,
                   const std::string& before = "", const std::string& after = "")
{
  return ("ply\nformat " + format + " 1.0\n" + before + "element vertex " + vertices +
          "\nproperty float x\nproperty float y\nproperty float z\n" + after +
          "end_header\n");
}

std::string gridInfo(const std::string& cols, const std::string& rows)
{
  return ("obj_info num_cols " + cols + "\nobj_info num_rows " + rows + "\n");
}

std::string rangeGrid(const std::string& cells)
{
  return ("element range_grid " + cells + "\nproperty list uchar int vertex_indices\n");
}

/** A small XYZI test cloud with varied values. */
pcl::PointCloud<pcl::PointXYZI> makeCloud(std::size_t n, std::uint32_t seed)
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

void expectSameXYZI(const pcl::PointCloud<pcl::PointXYZI>& a,
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

double rotationAngleDeg(const Eigen::Matrix4d& t)
{
  const double c = std::clamp((t.topLeftCorner<3, 3>().trace() - 1.0) / 2.0, -1.0, 1.0);
  return (std::acos(c) * 180.0 / M_PI);
}

} // namespace

/* ================================ real data ==================================== */

TEST(CloudIoData, Hdl32PcdWithIntensity)
{
  const std::vector<std::pair<std::string, std::size_t>> files = {
      {"lidar/hdl32_fastgicp/251370668.pcd", 69088},
      {"lidar/hdl32_fastgicp/251371071.pcd", 69792}};
  for (const auto& file : files)
    PCL_PHASER_REQUIRE_DATA(file.first);
  for (const auto& [relative, count] : files) {
    const std::string path = dataPath(relative);
    pcl::PCLPointCloud2 blob;
    std::string error;
    ASSERT_TRUE(loadCloud(path, blob, &error)) << error;
    EXPECT_EQ(blob.width * blob.height, count);
    EXPECT_EQ(blob.height, 1u);
    expectConsistent(blob, path);
    const CloudFieldInfo info = getCloudFieldInfo(blob);
    EXPECT_EQ(info.names, (std::vector<std::string>{"x", "y", "z", "intensity"}));
    EXPECT_TRUE(info.has_xyz);
    EXPECT_TRUE(info.has_intensity);
    EXPECT_FALSE(info.has_rgb);
    EXPECT_FALSE(info.has_normals);

    pcl::PointCloud<pcl::PointXYZI> cloud;
    ASSERT_TRUE(loadCloud(path, cloud, &error)) << error;
    EXPECT_EQ(cloud.size(), count);
    EXPECT_TRUE(cloud.is_dense);
    for (const auto& p : cloud)
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  }
}

TEST(CloudIoData, KittiBinWithReflectance)
{
  const std::vector<std::pair<std::string, std::size_t>> files = {
      {"lidar/kitti_raw_hdl64/0000000000.bin", 122626},
      {"lidar/kitti_raw_hdl64/0000000001.bin", 122619}};
  for (const auto& file : files)
    PCL_PHASER_REQUIRE_DATA(file.first);
  for (const auto& [relative, count] : files) {
    const std::string path = dataPath(relative);
    EXPECT_EQ(getCloudFormat(path), CloudFormat::KITTI_BIN);
    pcl::PCLPointCloud2 blob;
    std::string error;
    ASSERT_TRUE(loadCloud(path, blob, &error)) << error;
    EXPECT_EQ(blob.width, count);
    EXPECT_EQ(blob.width, fs::file_size(path) / 16);
    EXPECT_EQ(blob.height, 1u);
    expectConsistent(blob, path);
    EXPECT_EQ(getCloudFieldInfo(blob).names,
              (std::vector<std::string>{"x", "y", "z", "intensity"}));

    pcl::PointCloud<pcl::PointXYZI> cloud;
    ASSERT_TRUE(loadCloud(path, cloud, &error)) << error;
    ASSERT_EQ(cloud.size(), count);
    EXPECT_TRUE(cloud.is_dense);
    float lo = std::numeric_limits<float>::max(), hi = -lo, max_range = 0.0f;
    for (const auto& p : cloud) {
      lo = std::min(lo, p.intensity);
      hi = std::max(hi, p.intensity);
      max_range = std::max(max_range, p.getVector3fMap().norm());
    }
    EXPECT_GE(lo, 0.0f);
    EXPECT_LE(hi, 1.0f);
    EXPECT_GT(hi, 0.5f); // real reflectance, not garbage or zeros
    EXPECT_GT(max_range, 50.0f);
    EXPECT_LT(max_range, 130.0f); // HDL-64E range: metres, little-endian floats

    pcl::PointCloud<pcl::PointXYZ> xyz; // a type without intensity works too
    ASSERT_TRUE(loadCloud(path, xyz, &error)) << error;
    ASSERT_EQ(xyz.size(), count);
    EXPECT_EQ(xyz[1234].x, cloud[1234].x);
  }
}

TEST(CloudIoData, KittiSyntheticPlyAndTransform)
{
  const std::string a = "lidar/kitti_synthetic_gt/cloud049.ply";
  const std::string b = "lidar/kitti_synthetic_gt/cloud050.ply";
  const std::string t = "lidar/kitti_synthetic_gt/T_cloud050_cloud049_procrustes.txt";
  PCL_PHASER_REQUIRE_DATA(a);
  PCL_PHASER_REQUIRE_DATA(b);
  PCL_PHASER_REQUIRE_DATA(t);
  std::string error;
  pcl::PCLPointCloud2 blob;
  ASSERT_TRUE(loadCloud(dataPath(a), blob, &error)) << error;
  EXPECT_EQ(blob.width * blob.height, 13701u);
  EXPECT_EQ(getCloudFieldInfo(blob).names,
            (std::vector<std::string>{"x", "y", "z", "intensity"}));

  pcl::PointCloud<pcl::PointXYZI> source, target;
  ASSERT_TRUE(loadCloud(dataPath(a), source, &error)) << error;
  ASSERT_TRUE(loadCloud(dataPath(b), target, &error)) << error;
  ASSERT_EQ(source.size(), 13701u);
  ASSERT_EQ(target.size(), 13701u);
  Eigen::Matrix4d transform;
  ASSERT_TRUE(loadTransform(dataPath(t), transform, &error)) << error;
  // Points correspond index by index: T maps cloud049 onto cloud050 up to noise.
  double sum = 0.0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const Eigen::Vector4d p = source[i].getVector4fMap().cast<double>();
    const Eigen::Vector4d q = target[i].getVector4fMap().cast<double>();
    sum += ((transform * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0)).head<3>() -
            q.head<3>())
               .norm();
  }
  EXPECT_LT(sum / static_cast<double>(source.size()), 0.5);
}

TEST(CloudIoData, BunnyPlyWithRangeGrid)
{
  // PCL's PLY reader understands the range_grid element: it returns the scan as an
  // organized num_cols x num_rows (512 x 400) cloud, NaN where the grid has no vertex.
  // PCL reports is_dense = true for it; loadCloud corrects that to false.
  const std::vector<std::pair<std::string, std::size_t>> files = {
      {"object/stanford_bunny/bun000.ply", 40256},
      {"object/stanford_bunny/bun045.ply", 40097}};
  for (const auto& file : files)
    PCL_PHASER_REQUIRE_DATA(file.first);
  for (const auto& [relative, vertices] : files) {
    const std::string path = dataPath(relative);
    pcl::PCLPointCloud2 blob;
    std::string error;
    ASSERT_TRUE(loadCloud(path, blob, &error)) << error;
    expectConsistent(blob, path);
    EXPECT_EQ(blob.width, 512u);
    EXPECT_EQ(blob.height, 400u);
    EXPECT_EQ(blob.is_dense, 0);
    EXPECT_EQ(getCloudFieldInfo(blob).names, (std::vector<std::string>{"x", "y", "z"}));

    pcl::PointCloud<pcl::PointXYZ> cloud;
    ASSERT_TRUE(loadCloud(path, cloud, &error)) << error;
    EXPECT_TRUE(cloud.isOrganized());
    EXPECT_FALSE(cloud.is_dense);
    EXPECT_EQ(countFinite(cloud), vertices);

    pcl::PointCloud<pcl::PointXYZ> finite;
    pcl::Indices kept;
    pcl::removeNaNFromPointCloud(cloud, finite, kept); // relies on is_dense == false
    ASSERT_EQ(finite.size(), vertices);
    Eigen::Vector3f lo = finite[0].getVector3fMap(), hi = lo;
    for (const auto& p : finite) {
      lo = lo.cwiseMin(p.getVector3fMap());
      hi = hi.cwiseMax(p.getVector3fMap());
    }
    const float extent = (hi - lo).maxCoeff();
    EXPECT_GT(extent, 0.1f); // the bunny is about 0.15 m: metres, not millimetres
    EXPECT_LT(extent, 0.3f);
  }
}

TEST(CloudIoData, PclBunnyPcdWithNormals)
{
  const std::string bun0 = "pcl/bun0.pcd";
  const std::string bun4 = "pcl/bun4.pcd";
  PCL_PHASER_REQUIRE_DATA(bun0);
  PCL_PHASER_REQUIRE_DATA(bun4);
  std::string error;
  pcl::PCLPointCloud2 blob;
  ASSERT_TRUE(loadCloud(dataPath(bun0), blob, &error)) << error;
  EXPECT_EQ(blob.width * blob.height, 397u);
  const CloudFieldInfo info = getCloudFieldInfo(blob);
  EXPECT_TRUE(info.has_normals);
  EXPECT_TRUE(info.has_xyz);
  EXPECT_FALSE(info.has_intensity);
  EXPECT_TRUE(hasField(blob, "curvature"));

  pcl::PointCloud<pcl::PointNormal> normals;
  ASSERT_TRUE(loadCloud(dataPath(bun0), normals, &error)) << error;
  ASSERT_EQ(normals.size(), 397u);
  EXPECT_NEAR(normals[0].getNormalVector3fMap().norm(), 1.0f, 1e-3f);
  EXPECT_FLOAT_EQ(normals[0].x, 0.0054215998f);

  pcl::PCLPointCloud2 old_version; // "VERSION .5", no VIEWPOINT
  ASSERT_TRUE(loadCloud(dataPath(bun4), old_version, &error)) << error;
  EXPECT_EQ(old_version.width * old_version.height, 361u);
  EXPECT_FALSE(getCloudFieldInfo(old_version).has_normals);
}

TEST(CloudIoData, OrganizedKinectFramesWithNaN)
{
  const std::vector<std::string> files = {"pcl/frame_20121214T142255.814212.pcd",
                                          "pcl/frame_20121214T142256.068683.pcd"};
  for (const auto& file : files)
    PCL_PHASER_REQUIRE_DATA(file);
  for (const auto& relative : files) {
    const std::string path = dataPath(relative);
    pcl::PCLPointCloud2 blob;
    std::string error;
    ASSERT_TRUE(loadCloud(path, blob, &error)) << error;
    expectConsistent(blob, path);
    EXPECT_EQ(blob.width, 640u);
    EXPECT_EQ(blob.height, 480u);
    EXPECT_EQ(blob.is_dense, 0);
    const CloudFieldInfo info = getCloudFieldInfo(blob);
    EXPECT_TRUE(info.has_rgb);
    EXPECT_TRUE(hasField(blob, "rgba"));
    EXPECT_FALSE(info.has_intensity);

    pcl::PointCloud<pcl::PointXYZRGBA> rgba;
    ASSERT_TRUE(loadCloud(path, rgba, &error)) << error;
    EXPECT_TRUE(rgba.isOrganized());
    EXPECT_EQ(rgba.width, 640u);
    EXPECT_FALSE(rgba.is_dense);

    pcl::PointCloud<pcl::PointXYZ> xyz;
    ASSERT_TRUE(loadCloud(path, xyz, &error)) << error;
    const std::size_t finite = countFinite(xyz);
    EXPECT_GT(finite, 250000u); // ~271k finite of 307,200
    EXPECT_LT(finite, 307200u);

    // PCL maps the file's rgba onto PointXYZRGB's rgb field.
    pcl::PointCloud<pcl::PointXYZRGB> rgb;
    ASSERT_TRUE(loadCloud(path, rgb, &error)) << error;
    std::size_t same_colour = 0, coloured = 0;
    for (std::size_t i = 0; i < rgb.size(); i += 97) {
      same_colour += (rgb[i].rgba & 0xFFFFFFu) == (rgba[i].rgba & 0xFFFFFFu);
      coloured += (rgba[i].rgba & 0xFFFFFFu) != 0;
    }
    EXPECT_EQ(same_colour, (rgb.size() + 96) / 97);
    EXPECT_GT(coloured, 0u);
  }
}

TEST(CloudIoData, OfficeKeypointsPcd)
{
  const std::vector<std::pair<std::string, std::size_t>> files = {
      {"pcl/office1_keypoints.pcd", 1318}, {"pcl/office2_keypoints.pcd", 1123}};
  for (const auto& file : files)
    PCL_PHASER_REQUIRE_DATA(file.first);
  for (const auto& [relative, count] : files) {
    pcl::PointCloud<pcl::PointXYZI> cloud;
    std::string error;
    ASSERT_TRUE(loadCloud(dataPath(relative), cloud, &error)) << error;
    EXPECT_EQ(cloud.size(), count);
  }
}

TEST(TransformIoData, LoadsEveryDataTransform)
{
  PCL_PHASER_REQUIRE_DATA("lidar/hdl32_fastgicp/relative.txt");
  std::vector<std::string> files;
  for (const auto& entry :
       fs::recursive_directory_iterator(pcl_phaser::test::dataDir())) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && entry.path().extension() == ".txt" &&
        (name.rfind("T_", 0) == 0 || name == "relative.txt"))
      files.push_back(entry.path().string());
  }
  EXPECT_GE(files.size(), 4u);
  for (const std::string& path : files) {
    Eigen::Matrix4d t;
    std::string error;
    ASSERT_TRUE(loadTransform(path, t, &error)) << error;
    EXPECT_EQ(t.row(3), Eigen::RowVector4d(0, 0, 0, 1)) << path;
    const Eigen::Matrix3d r = t.topLeftCorner<3, 3>();
    EXPECT_NEAR(r.determinant(), 1.0, 1e-4) << path;
  }

  std::string error;
  Eigen::Matrix4d relative;
  ASSERT_TRUE(
      loadTransform(dataPath("lidar/hdl32_fastgicp/relative.txt"), relative, &error))
      << error;
  EXPECT_DOUBLE_EQ(relative(0, 3), 0.485657);
  EXPECT_DOUBLE_EQ(relative(1, 0), -0.0108468);
  EXPECT_NEAR(rotationAngleDeg(relative), 0.7, 0.1);

  if (pcl_phaser::test::haveData("object/stanford_bunny/T_bun000_bun045.txt")) {
    Eigen::Matrix4d bunny;
    ASSERT_TRUE(loadTransform(dataPath("object/stanford_bunny/T_bun000_bun045.txt"),
                              bunny, &error))
        << error;
    EXPECT_NEAR(rotationAngleDeg(bunny), 34.3, 0.1);
    EXPECT_NEAR((bunny.topRightCorner<3, 1>().norm()), 0.053, 0.001);
  }
  const std::string kitti =
      "lidar/kitti_synthetic_gt/T_cloud050_cloud049_procrustes.txt";
  if (pcl_phaser::test::haveData(kitti)) {
    Eigen::Matrix4d t;
    ASSERT_TRUE(loadTransform(dataPath(kitti), t, &error)) << error;
    EXPECT_NEAR(rotationAngleDeg(t), 154.0, 1.0);
    EXPECT_NEAR(t(1, 3), -1.0, 1e-3);
    EXPECT_NEAR(t(2, 3), 2.0, 1e-3);
  }
}

TEST(CloudIoTestData, EnvironmentOverridesDataDir)
{
  TempDir tmp;
  const char* old = std::getenv("PCL_PHASER_DATA");
  const std::string saved = old ? old : "";
  const std::string dir = tmp.file("data");
  fs::create_directories(dir + "/sub");
  writeFile(dir + "/sub/a.txt", "x");
  ::setenv("PCL_PHASER_DATA", dir.c_str(), 1);
  EXPECT_EQ(pcl_phaser::test::dataDir(), dir);
  EXPECT_TRUE(pcl_phaser::test::haveData("sub/a.txt"));
  EXPECT_FALSE(pcl_phaser::test::haveData("sub/missing.txt"));
  EXPECT_EQ(dataPath("sub/a.txt"),
            fs::path(dir + "/sub/a.txt").lexically_normal().string());
  if (old)
    ::setenv("PCL_PHASER_DATA", saved.c_str(), 1);
  else
    ::unsetenv("PCL_PHASER_DATA");
}

/* ============================== formats, fields ================================ */

TEST(CloudIo, FormatFromExtension)
{
  EXPECT_EQ(getCloudFormat("a.pcd"), CloudFormat::PCD);
  EXPECT_EQ(getCloudFormat("/x/y/A.PCD"), CloudFormat::PCD);
  EXPECT_EQ(getCloudFormat("scan.Ply"), CloudFormat::PLY);
  EXPECT_EQ(getCloudFormat("0000000000.bin"), CloudFormat::KITTI_BIN);
  EXPECT_EQ(getCloudFormat("cloud.xyz"), CloudFormat::UNKNOWN);
  EXPECT_EQ(getCloudFormat("/dir.pcd/cloud"), CloudFormat::UNKNOWN);
  EXPECT_EQ(getCloudFormat(""), CloudFormat::UNKNOWN);
}

TEST(CloudIo, FieldInfoOnBlobWithoutFields)
{
  const pcl::PCLPointCloud2 empty; // pcl::getFieldsList would read fields[0] here
  const CloudFieldInfo info = getCloudFieldInfo(empty);
  EXPECT_TRUE(info.names.empty());
  EXPECT_FALSE(info.has_xyz || info.has_intensity || info.has_rgb || info.has_normals);
  EXPECT_FALSE(hasField(empty, "x"));
}

/* =============================== bad input ===================================== */

TEST(CloudIoBadInput, MissingFile)
{
  TempDir tmp;
  for (const char* name :
       {"missing.pcd", "missing.ply", "missing.bin", "missing.xyz"}) {
    pcl::PCLPointCloud2 blob;
    std::string error;
    EXPECT_FALSE(loadCloud(tmp.file(name), blob, &error));
    EXPECT_NE(error.find("no such file"), std::string::npos) << error;
    EXPECT_NE(error.find(name), std::string::npos) << error;
    pcl::PointCloud<pcl::PointXYZ> cloud;
    EXPECT_FALSE(loadCloud(tmp.file(name), cloud)); // a null error pointer is fine
  }
  std::string error;
  pcl::PCLPointCloud2 blob;
  EXPECT_FALSE(loadCloud("", blob, &error));
  EXPECT_FALSE(error.empty());
}

TEST(CloudIoBadInput, Directory)
{
  TempDir tmp;
  for (const char* name : {"dir.pcd", "dir.ply", "dir.bin"}) {
    fs::create_directories(tmp.file(name));
    pcl::PCLPointCloud2 blob;
    std::string error;
    EXPECT_FALSE(loadCloud(tmp.file(name), blob, &error)); // PCL alone hangs on .pcd
    EXPECT_NE(error.find("directory"), std::string::npos) << error;
  }
}

TEST(CloudIoBadInput, UnknownOrMissingExtension)
{
  TempDir tmp;
  writeFile(tmp.file("cloud.xyz"), "1 2 3\n");
  writeFile(tmp.file("cloud"), "1 2 3\n");
  pcl::PCLPointCloud2 blob;
  std::string error;
  EXPECT_FALSE(loadCloud(tmp.file("cloud.xyz"), blob, &error));
  EXPECT_NE(error.find("unsupported extension '.xyz'"), std::string::npos) << error;
  EXPECT_FALSE(loadCloud(tmp.file("cloud"), blob, &error));
  EXPECT_NE(error.find("no file extension"), std::string::npos) << error;
}

TEST(CloudIoBadInput, EmptyFiles)
{
  TempDir tmp;
  for (const char* name : {"empty.pcd", "empty.ply", "empty.bin"}) {
    writeFile(tmp.file(name), "");
    pcl::PCLPointCloud2 blob;
    std::string error;
    EXPECT_FALSE(loadCloud(tmp.file(name), blob, &error)); // PCL segfaults on .pcd
    EXPECT_NE(error.find("empty"), std::string::npos) << error;
  }
}

TEST(CloudIoBadInput, GarbagePcdAndPly)
{
  TempDir tmp;
  QuietPcl quiet;
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    const std::string bytes = randomBytes(64 + seed * 250, seed);
    for (const char* name : {"garbage.pcd", "garbage.ply"}) {
      writeFile(tmp.file(name), bytes);
      pcl::PCLPointCloud2 blob;
      std::string error;
      EXPECT_FALSE(loadCloud(tmp.file(name), blob, &error)) << name << " seed " << seed;
      EXPECT_NE(error.find("not a valid"), std::string::npos) << error;
    }
  }
  // Garbage after a plausible first line, and printable garbage.
  writeFile(tmp.file("magic.pcd"), "# .PCD v0.7\n" + randomBytes(3000, 99));
  writeFile(tmp.file("magic.ply"), "ply\n" + randomBytes(3000, 98));
  writeFile(tmp.file("text.pcd"), "hello world\nthis is not a cloud\n");
  writeFile(tmp.file("text.ply"), "ply\nformat ascii 1.0\nhello\n");
  writeFile(tmp.file("magic_only.ply"), "ply\n");
  for (const char* name :
       {"magic.pcd", "magic.ply", "text.pcd", "text.ply", "magic_only.ply"}) {
    pcl::PCLPointCloud2 blob;
    std::string error;
    EXPECT_FALSE(loadCloud(tmp.file(name), blob, &error)) << name;
    EXPECT_FALSE(error.empty());
  }
}

TEST(CloudIoBadInput, KittiBinSizes)
{
  TempDir tmp;
  for (const std::size_t size : {1u, 15u, 17u, 4099u}) {
    writeFile(tmp.file("odd.bin"), randomBytes(size, static_cast<std::uint32_t>(size)));
    pcl::PCLPointCloud2 blob;
    std::string error;
    EXPECT_FALSE(loadCloud(tmp.file("odd.bin"), blob, &error)) << size;
    EXPECT_NE(error.find("not a multiple of 16"), std::string::npos) << error;
  }
  // A .bin has no header: random bytes of a valid size load (with NaN/Inf maybe),
  // and is_dense tells whether they are all finite.
  writeFile(tmp.file("random.bin"), randomBytes(4096, 7));
  pcl::PointCloud<pcl::PointXYZI> cloud;
  std::string error;
  ASSERT_TRUE(loadCloud(tmp.file("random.bin"), cloud, &error)) << error;
  EXPECT_EQ(cloud.size(), 256u);
  bool finite = true;
  for (const auto& p : cloud)
    finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  EXPECT_EQ(cloud.is_dense, finite);

  const std::vector<float> one_nan = {1, 2, 3, 0.5f, std::nanf(""), 0, 0, 0};
  writeFile(tmp.file("nan.bin"), bytesOf(one_nan));
  ASSERT_TRUE(loadCloud(tmp.file("nan.bin"), cloud, &error)) << error;
  EXPECT_EQ(cloud.size(), 2u);
  EXPECT_FALSE(cloud.is_dense);
  EXPECT_EQ(cloud[0].intensity, 0.5f);
}

TEST(CloudIoBadInput, CloudsWithoutXYZ)
{
  TempDir tmp;
  QuietPcl quiet;
  writeFile(tmp.file("ab.pcd"),
            pcdHeader("a b", "4 4", "F F", "1 1", "2", "1", "2", "ascii") +
                "1 2\n3 4\n");
  writeFile(tmp.file("xy.pcd"),
            pcdHeader("x y", "4 4", "F F", "1 1", "1", "1", "1", "ascii") + "1 2\n");
  writeFile(tmp.file("a.ply"), "ply\nformat ascii 1.0\nelement vertex 2\n"
                               "property float a\nend_header\n1\n2\n");
  writeFile(tmp.file("face.ply"), "ply\nformat ascii 1.0\nelement face 1\n"
                                  "property list uchar int vertex_indices\nend_header\n"
                                  "3 0 1 2\n");
  for (const char* name : {"ab.pcd", "xy.pcd", "a.ply", "face.ply"}) {
    pcl::PCLPointCloud2 blob;
    std::string error;
    EXPECT_FALSE(loadCloud(tmp.file(name), blob, &error)) << name;
    EXPECT_TRUE(error.find("x/y/z") != std::string::npos ||
                error.find("no vertex element") != std::string::npos)
        << error;
  }
}

TEST(CloudIoBadInput, PcdHeadersThatLie)
{
  TempDir tmp;
  QuietPcl quiet;
  const std::string twelve = randomBytes(12, 3);
  const std::string xyz = "x y z", f4 = "4 4 4", fff = "F F F", ones = "1 1 1";
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      // PCL would allocate 12 GB for this before noticing the file is short.
      {"points_1e9.pcd", xyzPcdHeader("1000000000", "binary") + twelve,
       "only 12 bytes of data follow"},
      {"points_2pow32.pcd",
       pcdHeader(xyz, f4, fff, ones, "4294967296", "1", "4294967296", "binary") +
           twelve,
       "too many points"},
      {"wh_overflow.pcd",
       pcdHeader(xyz, f4, fff, ones, "4294967296", "4294967296", "0", "binary"),
       "WIDTH x HEIGHT"},
      {"truncated_binary.pcd", xyzPcdHeader("1000", "binary") + "abc", "truncated"},
      {"truncated_compressed.pcd",
       xyzPcdHeader("1000", "binary_compressed") + "abcdefghijklmnop", "truncated"},
      {"compressed_size_block_missing.pcd",
       xyzPcdHeader("1000", "binary_compressed") + "abc", "missing its size block"},
      {"compressed_claims_2GB.pcd",
       xyzPcdHeader("1000", "binary_compressed") +
           bytesOf(std::vector<std::uint32_t>{0x7fffffffu, 0x7fffffffu}) + "abcdefgh",
       "truncated"},
      {"compressed_wrong_size.pcd",
       xyzPcdHeader("1000", "binary_compressed") +
           bytesOf(std::vector<std::uint32_t>{4, 999}) + "abcd",
       "decompresses to 999 bytes"},
      {"compressed_ratio.pcd",
       xyzPcdHeader("100000000", "binary_compressed") +
           bytesOf(std::vector<std::uint32_t>{4, 1200000000u}) + "abcd",
       "too small to hold"},
      {"ascii_claims_more.pcd", xyzPcdHeader("1000000", "ascii") + "1 2 3\n",
       "truncated"},
      {"short_ascii.pcd", xyzPcdHeader("3", "ascii") + "1 2 3\n4 5\n",
       "PCL's PCD reader rejected"},
      {"wh_mismatch.pcd", pcdHeader(xyz, f4, fff, ones, "10", "10", "50", "ascii"),
       "WIDTH x HEIGHT (10 x 10) != POINTS (50)"},
      {"size_mismatch.pcd", pcdHeader(xyz, "4 4", fff, ones, "1", "1", "1", "ascii"),
       "SIZE is missing or does not list"},
      {"bad_type.pcd", pcdHeader(xyz, f4, "F F Q", ones, "1", "1", "1", "ascii"),
       "TYPE 'Q'"},
      {"float16.pcd",
       pcdHeader(xyz, "2 2 2", fff, ones, "1", "1", "1", "binary") + "123456",
       "invalid SIZE 2 for TYPE F"},
      {"count_zero.pcd", pcdHeader(xyz, f4, fff, "0 1 1", "1", "1", "1", "ascii"),
       "invalid COUNT 0"},
      {"negative_points.pcd", xyzPcdHeader("-1", "binary") + twelve,
       "one non-negative integer"},
      {"no_data_type.pcd",
       "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nPOINTS 1\nDATA\n",
       "DATA line without a type"},
      {"no_data_line.pcd",
       "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nPOINTS 1\n",
       "no DATA line"},
      {"no_fields.pcd", "VERSION 0.7\nWIDTH 1\nPOINTS 1\nDATA ascii\n1 2 3\n",
       "no FIELDS"},
      {"unknown_data.pcd", xyzPcdHeader("1", "fancy") + twelve,
       "unknown DATA type 'fancy'"},
      {"control_character.pcd",
       pcdHeader("x\vy z", f4, fff, ones, "1", "1", "1", "ascii") + "1 2 3\n",
       "control character"},
  };
  for (const auto& [name, bytes, expected] : cases) {
    writeFile(tmp.file(name), bytes);
    pcl::PCLPointCloud2 blob;
    std::string error;
    EXPECT_FALSE(loadCloud(tmp.file(name), blob, &error)) << name;
    EXPECT_NE(error.find(expected), std::string::npos) << name << ": " << error;
    EXPECT_NE(error.find(name), std::string::npos) << error;
  }
}

TEST(CloudIoBadInput, PlyHeadersThatLie)
{
  TempDir tmp;
  QuietPcl quiet;
  const std::string ascii = "ascii", binary = "binary_little_endian";
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      // PCL would allocate and zero 12 GB for this one.
      {"vertices_1e9.ply", plyXYZ(binary, "1000000000") + "abc", "only 3 bytes follow"},
      {"vertices_5e9.ply", plyXYZ(binary, "5000000000") + "abc", "too many vertices"},
      {"short_ascii.ply", plyXYZ(ascii, "3") + "1 2 3\n", "truncated"},
      // More vertices than the obj_info grid: PCL would assert (abort).
      {"grid_too_small.ply", plyXYZ(ascii, "2", gridInfo("1", "1")) + "1 2 3\n4 5 6\n",
       "do not fit"},
      {"grid_huge.ply",
       plyXYZ(ascii, "1", gridInfo("100000", "100000"), rangeGrid("1")) +
           "1 2 3\n1 0\n",
       "range_grid has 1 cells"},
      {"grid_negative.ply", plyXYZ(ascii, "1", gridInfo("-5", "2")) + "1 2 3\n",
       "invalid obj_info num_cols"},
      {"grid_without_range_grid.ply",
       plyXYZ(ascii, "1", gridInfo("2", "2")) + "1 2 3\n", "but there are 1 vertices"},
      {"range_grid_bad_index.ply",
       plyXYZ(ascii, "1", gridInfo("2", "2"), rangeGrid("4")) +
           "1 2 3\n1 7\n0\n0\n1 -5\n",
       "index 7 is outside"},
      // PCL computes index * point_step in 32 bits: this index wraps its bounds check
      // and PCL reads 4 GB out of bounds (segfault).
      {"range_grid_index_wraps.ply",
       plyXYZ(ascii, "2", gridInfo("2", "2"), rangeGrid("4")) +
           "1 2 3\n4 5 6\n1 357913941\n0\n0\n1 0\n",
       "index 357913941 is outside"},
      {"range_grid_binary_bad_index.ply",
       plyXYZ(binary, "1", gridInfo("2", "1"), rangeGrid("2")) +
           bytesOf(std::vector<float>{1, 2, 3}) + std::string("\x01\x05\0\0\0\0", 6),
       "index 5 is outside"},
      {"range_grid_extra_values.ply",
       plyXYZ(ascii, "1", gridInfo("2", "1"), rangeGrid("2")) + "1 2 3\n1 0 7\n0\n",
       "has 3 values, expected 2"},
      {"range_grid_without_dims.ply",
       plyXYZ(ascii, "1", "", rangeGrid("2")) + "1 2 3\n1 0\n0\n", "without obj_info"},
      // PCL's obj_info handler asserts (aborts) on an indented obj_info line.
      {"indented_obj_info.ply",
       plyXYZ(ascii, "1", " obj_info num_cols 2\n") + "1 2 3\n",
       "starts with whitespace"},
      // uchar blue before red: PCL writes the packed rgb past the buffer (abort).
      {"blue_before_red.ply",
       plyXYZ(ascii, "2", "",
              "property uchar blue\nproperty uchar green\nproperty uchar red\n") +
           "1 2 3 4 5 6\n6 7 8 9 10 11\n",
       "red before blue"},
      {"blue_without_red.ply",
       plyXYZ(ascii, "2", "", "property uchar green\nproperty uchar blue\n") +
           "1 2 3 4 5\n6 7 8 9 10\n",
       "red before blue"},
      // PCL sizes list fields from the first vertex only: lists are not supported.
      {"vertex_list.ply",
       plyXYZ(ascii, "2", "", "property list uchar float extra\n") +
           "1 2 3 1 9\n4 5 6 3 9 9 9\n",
       "vertex list property"},
      {"no_end_header.ply", "ply\nformat ascii 1.0\nelement vertex 1\n",
       "no end_header"},
      {"no_format.ply", "ply\nelement vertex 1\nend_header\n1 2 3\n",
       "element before the format line"},
      {"bad_format.ply", "ply\nformat utf8 1.0\nelement vertex 0\nend_header\n",
       "unsupported format"},
      {"bad_type.ply", plyXYZ(ascii, "1", "", "property quad w\n") + "1 2 3 4\n",
       "unknown type"},
      {"bad_count.ply", plyXYZ(ascii, "-1") + "1 2 3\n", "invalid element line"},
      {"two_vertex_elements.ply",
       plyXYZ(ascii, "1", "", "element vertex 1\nproperty float x\n") + "1 2 3\n1\n",
       "more than one vertex element"},
  };
  for (const auto& [name, bytes, expected] : cases) {
    writeFile(tmp.file(name), bytes);
    pcl::PCLPointCloud2 blob;
    std::string error;
    EXPECT_FALSE(loadCloud(tmp.file(name), blob, &error)) << name;
    EXPECT_NE(error.find(expected), std::string::npos) << name << ": " << error;
  }
}

TEST(CloudIoBadInput, UnreadableFile)
{
  TempDir tmp;
  const std::string path = tmp.file("locked.pcd");
  writeFile(path, xyzPcdHeader("1", "ascii") + "1 2 3\n");
  fs::permissions(path, fs::perms::none);
  if (std::ifstream(path).is_open()) { // root ignores permissions
    fs::permissions(path, fs::perms::owner_all);
    GTEST_SKIP() << "running with privileges that ignore file permissions";
  }
  pcl::PCLPointCloud2 blob;
  std::string error;
  EXPECT_FALSE(loadCloud(path, blob, &error));
  EXPECT_NE(error.find("cannot open"), std::string::npos) << error;
  fs::permissions(path, fs::perms::owner_all);
}

TEST(CloudIoBadInput, TypedLoadRejectsDoubleXYZ)
{
  TempDir tmp;
  const std::string path = tmp.file("double.pcd");
  writeFile(path,
            pcdHeader("x y z", "8 8 8", "F F F", "1 1 1", "2", "1", "2", "ascii") +
                "1 2 3\n4 5 6\n");
  pcl::PCLPointCloud2 blob;
  std::string error;
  ASSERT_TRUE(loadCloud(path, blob, &error)) << error; // the blob keeps float64
  EXPECT_EQ(blob.fields[0].datatype, pcl::PCLPointField::FLOAT64);
  pcl::PointCloud<pcl::PointXYZ> cloud;
  EXPECT_FALSE(loadCloud(path, cloud, &error));
  EXPECT_NE(error.find("float32"), std::string::npos) << error;
}

TEST(CloudIoBadInput, ValidEmptyCloudLoads)
{
  TempDir tmp;
  QuietPcl quiet;
  const std::string path = tmp.file("zero.pcd");
  writeFile(path, xyzPcdHeader("0", "ascii"));
  pcl::PCLPointCloud2 blob;
  std::string error;
  ASSERT_TRUE(loadCloud(path, blob, &error)) << error;
  EXPECT_EQ(blob.width * blob.height, 0u);
  pcl::PointCloud<pcl::PointXYZ> cloud;
  ASSERT_TRUE(loadCloud(path, cloud, &error)) << error;
  EXPECT_TRUE(cloud.empty());
}

TEST(CloudIoBadInput, SmallRangeGridPlyIsOrganizedAndNotDense)
{
  TempDir tmp;
  const std::string path = tmp.file("grid.ply");
  writeFile(path, "ply\nformat ascii 1.0\nobj_info num_cols 2\nobj_info num_rows 2\n"
                  "element vertex 2\nproperty float x\nproperty float y\n"
                  "property float z\nelement range_grid 4\n"
                  "property list uchar int vertex_indices\nend_header\n"
                  "1 2 3\n4 5 6\n1 1\n0\n0\n1 0\n");
  pcl::PointCloud<pcl::PointXYZ> cloud;
  std::string error;
  ASSERT_TRUE(loadCloud(path, cloud, &error)) << error;
  ASSERT_EQ(cloud.width, 2u);
  ASSERT_EQ(cloud.height, 2u);
  EXPECT_FALSE(cloud.is_dense);
  EXPECT_EQ(cloud[0].x, 4.0f);
  EXPECT_TRUE(std::isnan(cloud[1].x));
  EXPECT_TRUE(std::isnan(cloud[2].x));
  EXPECT_EQ(cloud[3].x, 1.0f);
}

/* ============================ robustness sweeps ================================ */

namespace {

/** Small valid files of every flavour, as (name, bytes). */
std::vector<std::pair<std::string, std::string>> validSampleFiles(const TempDir& tmp)
{
  pcl::PointCloud<pcl::PointXYZI> cloud = makeCloud(12, 5);
  cloud[3].x = std::numeric_limits<float>::quiet_NaN();
  pcl::PointCloud<pcl::PointXYZI> organized = makeCloud(12, 6);
  organized.width = 4;
  organized.height = 3;
  std::vector<std::pair<std::string, std::string>> files;
  const auto add = [&](const std::string& name) {
    files.emplace_back(name, readFile(tmp.file(name)));
  };
  pcl::io::savePCDFileASCII(tmp.file("ascii.pcd"), cloud);
  add("ascii.pcd");
  pcl::io::savePCDFileBinary(tmp.file("binary.pcd"), cloud);
  add("binary.pcd");
  pcl::io::savePCDFileBinaryCompressed(tmp.file("compressed.pcd"), organized);
  add("compressed.pcd");
  pcl::io::savePLYFileASCII(tmp.file("ascii.ply"), makeCloud(12, 7));
  add("ascii.ply");
  pcl::io::savePLYFileBinary(tmp.file("binary.ply"), makeCloud(12, 8));
  add("binary.ply");
  // Colour and normals: PCL packs uchar red/green/blue(/alpha) into rgb(a).
  pcl::PointCloud<pcl::PointXYZRGBNormal> colour;
  for (int i = 0; i < 8; ++i) {
    pcl::PointXYZRGBNormal p;
    p.x = static_cast<float>(i);
    p.y = 2.0f * static_cast<float>(i);
    p.z = -1.0f;
    p.r = static_cast<std::uint8_t>(30 * i);
    p.g = 7;
    p.b = 200;
    p.normal_x = 1.0f;
    colour.push_back(p);
  }
  pcl::io::savePLYFileBinary(tmp.file("colour_binary.ply"), colour);
  add("colour_binary.ply");
  pcl::io::savePLYFileASCII(tmp.file("colour_ascii.ply"), colour);
  add("colour_ascii.ply");
  pcl::io::savePCDFileBinaryCompressed(tmp.file("colour.pcd"), colour);
  add("colour.pcd");
  writeFile(tmp.file("grid.ply"),
            "ply\nformat ascii 1.0\nobj_info num_cols 2\nobj_info num_rows 2\n"
            "element vertex 2\nproperty float x\nproperty float y\n"
            "property float z\nelement range_grid 4\n"
            "property list uchar int vertex_indices\nend_header\n"
            "1 2 3\n4 5 6\n1 1\n0\n0\n1 0\n");
  add("grid.ply");
  writeFile(tmp.file("scan.bin"), bytesOf(std::vector<float>(48, 1.5f)));
  add("scan.bin");
  return (files);
}

} // namespace

TEST(CloudIoFuzz, EveryTruncation)
{
  TempDir tmp;
  QuietPcl quiet;
  for (const auto& [name, bytes] : validSampleFiles(tmp)) {
    ASSERT_FALSE(bytes.empty()) << name;
    pcl::PCLPointCloud2 full;
    std::string error;
    ASSERT_TRUE(loadCloud(tmp.file(name), full, &error)) << name << ": " << error;
    const std::string path = tmp.file("cut_" + name);
    for (std::size_t size = 0; size < bytes.size(); ++size) {
      writeFile(path, bytes.substr(0, size));
      loadAndCheckInvariants(path, name + " cut at " + std::to_string(size));
    }
  }
}

TEST(CloudIoFuzz, RandomByteChanges)
{
  TempDir tmp;
  QuietPcl quiet;
  std::mt19937 rng(20260101);
  for (const auto& [name, bytes] : validSampleFiles(tmp)) {
    const std::string path = tmp.file("mutated_" + name);
    std::uniform_int_distribution<std::size_t> where(0, bytes.size() - 1);
    std::uniform_int_distribution<int> value(0, 255), how_many(1, 4);
    for (int trial = 0; trial < 300; ++trial) {
      std::string mutated = bytes;
      for (int k = how_many(rng); k > 0; --k)
        mutated[where(rng)] = static_cast<char>(value(rng));
      writeFile(path, mutated);
      loadAndCheckInvariants(path, name + " trial " + std::to_string(trial));
    }
  }
}

TEST(CloudIoFuzz, HeaderNumberSweep)
{
  TempDir tmp;
  QuietPcl quiet;
  const std::vector<std::string> numbers = {"0",          "1",
                                            "2",          "3",
                                            "65535",      "2147483647",
                                            "2147483648", "4294967295",
                                            "4294967296", "99999999999",
                                            "-1",         "1e3",
                                            "abc",        ""};
  const std::string body = randomBytes(36, 11);
  for (const std::string& n : numbers) {
    for (const char* data : {"ascii", "binary", "binary_compressed"}) {
      writeFile(tmp.file("sweep.pcd"),
                pcdHeader("x y z", "4 4 4", "F F F", "1 1 1", n, "1", n, data) + body);
      loadAndCheckInvariants(tmp.file("sweep.pcd"), "pcd " + n + " " + data);
      writeFile(tmp.file("sweep2.pcd"),
                pcdHeader("x y z", n, "F F F", n, "3", "1", "3", data) + body);
      loadAndCheckInvariants(tmp.file("sweep2.pcd"), "pcd size/count " + n);
    }
    for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
      const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
      writeFile(tmp.file("sweep.ply"), std::string("ply\nformat ") + format +
                                           " 1.0\nelement vertex " + n + "\n" + xyz +
                                           "end_header\n" + body);
      loadAndCheckInvariants(tmp.file("sweep.ply"), "ply " + n + " " + format);
      writeFile(tmp.file("sweep_grid.ply"),
                std::string("ply\nformat ") + format + " 1.0\nobj_info num_cols " + n +
                    "\nobj_info num_rows 2\nelement vertex 2\n" + xyz +
                    "element range_grid " + n +
                    "\nproperty list uchar int vertex_indices\nend_header\n" + body);
      loadAndCheckInvariants(tmp.file("sweep_grid.ply"),
                             "ply grid " + n + " " + format);
    }
  }
}

/* ================================== save ======================================= */

TEST(CloudIoSave, RoundTripEveryFormat)
{
  TempDir tmp;
  const pcl::PointCloud<pcl::PointXYZI> cloud = makeCloud(100, 42);
  for (const char* name : {"out.pcd", "out.ply", "out.bin", "OUT.PCD"}) {
    std::string error;
    ASSERT_TRUE(saveCloud(tmp.file(name), cloud, &error)) << error;
    pcl::PointCloud<pcl::PointXYZI> back;
    ASSERT_TRUE(loadCloud(tmp.file(name), back, &error)) << error;
    expectSameXYZI(cloud, back);
  }
  // .pcd is binary, as promised
  EXPECT_NE(readFile(tmp.file("out.pcd")).find("DATA binary\n"), std::string::npos);
  EXPECT_EQ(fs::file_size(tmp.file("out.bin")), 100u * 16u);
}

TEST(CloudIoSave, OrganizedWithNaNKeepsShapeInPcd)
{
  TempDir tmp;
  pcl::PointCloud<pcl::PointXYZI> cloud = makeCloud(12, 1);
  cloud.width = 4;
  cloud.height = 3;
  cloud.is_dense = false;
  cloud[5].x = cloud[5].y = cloud[5].z = std::numeric_limits<float>::quiet_NaN();
  std::string error;
  ASSERT_TRUE(saveCloud(tmp.file("organized.pcd"), cloud, &error)) << error;
  pcl::PointCloud<pcl::PointXYZI> back;
  ASSERT_TRUE(loadCloud(tmp.file("organized.pcd"), back, &error)) << error;
  EXPECT_EQ(back.width, 4u);
  EXPECT_EQ(back.height, 3u);
  EXPECT_FALSE(back.is_dense);
  EXPECT_TRUE(std::isnan(back[5].x));
  EXPECT_EQ(back[6].y, cloud[6].y);
}

TEST(CloudIoSave, BinWithoutIntensityWritesZero)
{
  TempDir tmp;
  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.push_back(pcl::PointXYZ(1.0f, 2.0f, 3.0f));
  cloud.push_back(pcl::PointXYZ(-4.0f, 5.5f, 6.25f));
  std::string error;
  ASSERT_TRUE(saveCloud(tmp.file("xyz.bin"), cloud, &error)) << error;
  pcl::PointCloud<pcl::PointXYZI> back;
  ASSERT_TRUE(loadCloud(tmp.file("xyz.bin"), back, &error)) << error;
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].z, 6.25f);
  EXPECT_EQ(back[1].intensity, 0.0f);
}

/** A PointXYZINormal or PointXYZRGBNormal cloud whose every field holds an exactly
 *  representable value that differs from point to point (colour alpha 255). */
template <typename PointT>
pcl::PointCloud<PointT> makeNormalCloud(std::size_t n)
{
  pcl::PointCloud<PointT> cloud;
  for (std::size_t i = 0; i < n; ++i) {
    const float k = static_cast<float>(i);
    PointT p;
    p.x = 1.0f + k;
    p.y = -2.5f - k;
    p.z = 3.25f + 0.5f * k;
    p.normal_x = 0.5f;
    p.normal_y = -0.25f * static_cast<float>(i % 3);
    p.normal_z = 0.75f + 0.0625f * k;
    p.curvature = 0.125f * k;
    if constexpr (std::is_same_v<PointT, pcl::PointXYZINormal>) {
      p.intensity = 100.0f + 7.0f * k;
    } else {
      p.r = static_cast<std::uint8_t>(10 + i);
      p.g = static_cast<std::uint8_t>(200 - i);
      p.b = static_cast<std::uint8_t>(3 * i);
      p.a = 255;
    }
    cloud.push_back(p);
  }
  return (cloud);
}

template <typename PointT>
void expectSameNormalCloud(const pcl::PointCloud<PointT>& a,
                           const pcl::PointCloud<PointT>& b, const std::string& what)
{
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].x, b[i].x) << what << " " << i;
    EXPECT_EQ(a[i].y, b[i].y) << what << " " << i;
    EXPECT_EQ(a[i].z, b[i].z) << what << " " << i;
    EXPECT_EQ(a[i].normal_x, b[i].normal_x) << what << " " << i;
    EXPECT_EQ(a[i].normal_y, b[i].normal_y) << what << " " << i;
    EXPECT_EQ(a[i].normal_z, b[i].normal_z) << what << " " << i;
    EXPECT_EQ(a[i].curvature, b[i].curvature) << what << " " << i;
    if constexpr (std::is_same_v<PointT, pcl::PointXYZINormal>) {
      EXPECT_EQ(a[i].intensity, b[i].intensity) << what << " " << i;
    } else {
      EXPECT_EQ(a[i].r, b[i].r) << what << " " << i;
      EXPECT_EQ(a[i].g, b[i].g) << what << " " << i;
      EXPECT_EQ(a[i].b, b[i].b) << what << " " << i;
    }
  }
}

template <typename PointT>
void roundTripNormalCloud(const std::string& type_name)
{
  TempDir tmp;
  const pcl::PointCloud<PointT> cloud = makeNormalCloud<PointT>(17);
  for (const char* name : {"normals.pcd", "normals.ply"}) {
    const std::string what = type_name + " " + name;
    std::string error;
    ASSERT_TRUE(saveCloud(tmp.file(name), cloud, &error)) << what << ": " << error;
    pcl::PointCloud<PointT> back;
    ASSERT_TRUE(loadCloud(tmp.file(name), back, &error)) << what << ": " << error;
    expectSameNormalCloud(cloud, back, what);
    pcl::PCLPointCloud2 blob;
    ASSERT_TRUE(loadCloud(tmp.file(name), blob, &error)) << what << ": " << error;
    const CloudFieldInfo info = getCloudFieldInfo(blob);
    EXPECT_TRUE(info.has_xyz) << what;
    EXPECT_TRUE(info.has_normals) << what;
    EXPECT_TRUE(hasField(blob, "curvature")) << what;
  }
  // The PCD header describes the padding with positive counts only.
  const std::string pcd = readFile(tmp.file("normals.pcd"));
  const std::string header = pcd.substr(0, pcd.find("DATA binary\n"));
  const std::size_t count_line = header.find("\nCOUNT ");
  ASSERT_NE(count_line, std::string::npos) << header;
  const std::string counts =
      header.substr(count_line, header.find('\n', count_line + 1) - count_line);
  EXPECT_EQ(counts.find('-'), std::string::npos) << header;
  // Fields written in offset order; the PCD reader keeps the file's order.
  pcl::PCLPointCloud2 blob;
  std::string error;
  ASSERT_TRUE(loadCloud(tmp.file("normals.pcd"), blob, &error)) << error;
  for (std::size_t i = 1; i < blob.fields.size(); ++i)
    EXPECT_LE(blob.fields[i - 1].offset, blob.fields[i].offset) << header;
}

TEST(CloudIoSave, PointXYZINormalRoundTripsEveryField)
{
  roundTripNormalCloud<pcl::PointXYZINormal>("PointXYZINormal");
}

TEST(CloudIoSave, PointXYZRGBNormalRoundTripsEveryField)
{
  roundTripNormalCloud<pcl::PointXYZRGBNormal>("PointXYZRGBNormal");
}

TEST(CloudIoSave, BlobFieldsOutOfOffsetOrderWithPadding)
{
  // A hand-made blob: fields listed out of memory order, a gap between them and
  // padding at the end of the point (point_step 32).
  TempDir tmp;
  pcl::PCLPointCloud2 blob;
  const auto field = [](const std::string& name, std::uint32_t offset,
                        std::uint8_t datatype) {
    pcl::PCLPointField f;
    f.name = name;
    f.offset = offset;
    f.datatype = datatype;
    f.count = 1;
    return (f);
  };
  blob.fields = {field("z", 8, pcl::PCLPointField::FLOAT32),
                 field("label", 20, pcl::PCLPointField::UINT16),
                 field("x", 0, pcl::PCLPointField::FLOAT32),
                 field("y", 4, pcl::PCLPointField::FLOAT32),
                 field("weight", 12, pcl::PCLPointField::FLOAT64)};
  blob.point_step = 32;
  blob.width = 3;
  blob.height = 1;
  blob.row_step = blob.point_step * blob.width;
  blob.is_dense = 1;
  blob.data.assign(blob.row_step, 0);
  for (std::uint32_t i = 0; i < blob.width; ++i) {
    std::uint8_t* p = blob.data.data() + i * blob.point_step;
    const float xyz[3] = {1.5f * i, -2.0f - i, 0.25f + i};
    const double weight = 1e-3 * (i + 1);
    const std::uint16_t label = static_cast<std::uint16_t>(1000 + i);
    std::memcpy(p, xyz, sizeof(xyz));
    std::memcpy(p + 12, &weight, sizeof(weight));
    std::memcpy(p + 20, &label, sizeof(label));
  }
  const pcl::PCLPointCloud2 original = blob;
  std::string error;
  ASSERT_TRUE(saveCloud(tmp.file("blob.pcd"), blob, &error)) << error;
  EXPECT_EQ(blob.fields.size(), original.fields.size()); // the input is not touched
  EXPECT_EQ(blob.fields[0].name, "z");
  pcl::PCLPointCloud2 back;
  ASSERT_TRUE(loadCloud(tmp.file("blob.pcd"), back, &error)) << error;
  ASSERT_EQ(back.width, 3u);
  for (const char* name : {"x", "y", "z", "weight", "label"}) {
    const auto find = [&](const pcl::PCLPointCloud2& c) {
      return (
          std::find_if(c.fields.begin(), c.fields.end(),
                       [&](const pcl::PCLPointField& f) { return (f.name == name); }));
    };
    const auto a = find(original);
    const auto b = find(back);
    ASSERT_NE(b, back.fields.end()) << name;
    ASSERT_EQ(a->datatype, b->datatype) << name;
    const int size = pcl::getFieldSize(a->datatype);
    for (std::uint32_t i = 0; i < 3; ++i)
      EXPECT_EQ(0,
                std::memcmp(original.data.data() + i * original.point_step + a->offset,
                            back.data.data() + i * back.point_step + b->offset, size))
          << name << " " << i;
  }
}

TEST(CloudIoSave, Errors)
{
  TempDir tmp;
  QuietPcl quiet;
  const pcl::PointCloud<pcl::PointXYZI> cloud = makeCloud(5, 3);
  std::string error;
  EXPECT_FALSE(saveCloud(tmp.file("out.xyz"), cloud, &error));
  EXPECT_NE(error.find("unsupported extension"), std::string::npos) << error;
  EXPECT_FALSE(saveCloud(tmp.file("out"), cloud, &error));
  EXPECT_NE(error.find("no file extension"), std::string::npos) << error;
  EXPECT_FALSE(saveCloud(tmp.file("no/such/dir/out.pcd"), cloud, &error));
  EXPECT_NE(error.find("does not exist"), std::string::npos) << error;
  fs::create_directories(tmp.file("dir.pcd"));
  EXPECT_FALSE(saveCloud(tmp.file("dir.pcd"), cloud, &error));
  EXPECT_NE(error.find("directory"), std::string::npos) << error;
  EXPECT_FALSE(saveCloud("", cloud, &error));

  const pcl::PointCloud<pcl::PointXYZI> empty;
  EXPECT_FALSE(saveCloud(tmp.file("empty.pcd"), empty, &error));
  EXPECT_NE(error.find("empty"), std::string::npos) << error;

  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(cloud, blob);
  pcl::PCLPointCloud2 broken = blob;
  broken.data.resize(broken.data.size() / 2);
  for (const char* name : {"broken.pcd", "broken.ply", "broken.bin"}) {
    EXPECT_FALSE(saveCloud(tmp.file(name), broken, &error)) << name;
    EXPECT_NE(error.find("inconsistent"), std::string::npos) << error;
  }
  pcl::PCLPointCloud2 no_xyz = blob;
  for (auto& f : no_xyz.fields)
    f.name = "v_" + f.name;
  EXPECT_FALSE(saveCloud(tmp.file("noxyz.pcd"), no_xyz, &error));
  EXPECT_NE(error.find("x/y/z"), std::string::npos) << error;
}

/* =============================== transforms ==================================== */

TEST(TransformIo, ParsesBothShapes)
{
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  std::string text4, text3;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      char buffer[64];
      std::snprintf(buffer, sizeof(buffer), "%.17g ", r(i, j));
      text4 += buffer;
      text3 += buffer;
    }
    const std::string t = std::to_string(i + 1) + ".5\n";
    text4 += t;
    text3 += t;
  }
  text4 += "0 0 0 1\n";
  Eigen::Matrix4d m4, m3;
  std::string error;
  ASSERT_TRUE(parseTransform(text4, m4, &error)) << error;
  ASSERT_TRUE(parseTransform(text3, m3, &error)) << error;
  EXPECT_EQ(m4, m3);
  EXPECT_TRUE((m4.topLeftCorner<3, 3>().isApprox(r, 1e-15)));
  EXPECT_EQ(m4(2, 3), 3.5);
  EXPECT_EQ(m3.row(3), Eigen::RowVector4d(0, 0, 0, 1));

  // Comments, CRLF, tabs, a '+' sign and exponents; one number per line works too.
  Eigen::Matrix4d m;
  ASSERT_TRUE(parseTransform("# pose\r\n1 0 0 +1e-1\t# x\r\n0 1 0 2E0\r\n"
                             "0 0 1 -3\r\n0 0 0 1\r\n",
                             m, &error))
      << error;
  EXPECT_EQ(m(0, 3), 0.1);
  EXPECT_EQ(m(2, 3), -3.0);
  ASSERT_TRUE(parseTransform("1\n0\n0\n0\n0\n1\n0\n0\n0\n0\n1\n0\n", m, &error))
      << error;
  EXPECT_EQ(m, Eigen::Matrix4d::Identity());
}

TEST(TransformIo, RejectsBadTransforms)
{
  const Eigen::Matrix4d sentinel = Eigen::Matrix4d::Constant(7.0);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "found 0"},
      {"1 0 0 0 1 0 0 0 1", "found 9"},
      {"1 0 0 0 0 1 0 0 0 0 1 0 5", "found 13"},
      {"1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 0", "more than 16"},
      {"1 0 0 0 0 1 0 0 0 0 1 abc", "'abc' is not a number"},
      {"1 0 0 0 0 1 0 0 0 0 1 1.0.0", "is not a number"},
      {"1,0,0,0 0,1,0,0 0,0,1,0", "is not a number"},
      {"1 0 0 0 0 1 0 0 0 0 1 nan", "non-finite"},
      {"1 0 0 inf 0 1 0 0 0 0 1 0", "non-finite"},
      {"1.01 0 0 0 0 1 0 0 0 0 1 0", "not orthonormal"},
      {"0 0 0 0 0 0 0 0 0 0 0 0", "not orthonormal"},
      {"1 0 0 0 0 1 0 0 0 0 -1 0", "reflection"},
      {"1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 2", "last row"},
      {"1 0 0 0 0 1 0 0 0 0 1 0 1 0 0 1", "last row"},
  };
  for (const auto& [text, expected] : cases) {
    Eigen::Matrix4d m = sentinel;
    std::string error;
    EXPECT_FALSE(parseTransform(text, m, &error)) << text;
    EXPECT_NE(error.find(expected), std::string::npos) << text << " -> " << error;
    EXPECT_EQ(m, sentinel) << "unchanged on failure";
  }
  // The tolerance decides how orthonormal is orthonormal enough.
  Eigen::Matrix4d m;
  std::string error;
  const std::string slightly_off = "1.001 0 0 0 0 1 0 0 0 0 1 0";
  EXPECT_FALSE(parseTransform(slightly_off, m, &error));
  EXPECT_TRUE(parseTransform(slightly_off, m, &error, 1e-2)) << error;
  EXPECT_FALSE(parseTransform("1 0 0 0 0 1 0 0 0 0 1 0", m, &error, -1.0));
  EXPECT_NE(error.find("tolerance"), std::string::npos) << error;
}

TEST(TransformIo, FilesAndRoundTrip)
{
  TempDir tmp;
  Eigen::Matrix4d m;
  std::string error;
  EXPECT_FALSE(loadTransform(tmp.file("missing.txt"), m, &error));
  EXPECT_NE(error.find("no such file"), std::string::npos) << error;
  fs::create_directories(tmp.file("dir.txt"));
  EXPECT_FALSE(loadTransform(tmp.file("dir.txt"), m, &error));
  EXPECT_NE(error.find("directory"), std::string::npos) << error;
  writeFile(tmp.file("empty.txt"), "");
  EXPECT_FALSE(loadTransform(tmp.file("empty.txt"), m, &error));
  EXPECT_NE(error.find("empty"), std::string::npos) << error;
  writeFile(tmp.file("big.txt"), std::string(2u << 20, ' '));
  EXPECT_FALSE(loadTransform(tmp.file("big.txt"), m, &error));
  EXPECT_NE(error.find("too large"), std::string::npos) << error;
  writeFile(tmp.file("garbage.txt"), randomBytes(500, 4));
  EXPECT_FALSE(loadTransform(tmp.file("garbage.txt"), m, &error));
  EXPECT_NE(error.find("garbage.txt"), std::string::npos) << error;

  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(2.7, Eigen::Vector3d(-0.2, 0.9, 0.4).normalized())
          .toRotationMatrix();
  t.topRightCorner<3, 1>() = Eigen::Vector3d(0.1, -123.456789, 1e-7);
  ASSERT_TRUE(saveTransform(tmp.file("t.txt"), t, &error)) << error;
  ASSERT_TRUE(loadTransform(tmp.file("t.txt"), m, &error)) << error;
  EXPECT_EQ(m, t); // shortest round-trip formatting is exact
  EXPECT_FALSE(saveTransform(tmp.file("no/such/dir/t.txt"), t, &error));
  EXPECT_NE(error.find("cannot open"), std::string::npos) << error;
}
