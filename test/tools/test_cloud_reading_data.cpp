/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * cloud reading on the shared real files: every format and field layout.
 */
#include "cloud_reading_test_support.h"

using namespace pcl::phaser::test;

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
    EXPECT_EQ(fieldNames(blob), (std::vector<std::string>{"x", "y", "z", "intensity"}));

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
    EXPECT_EQ(fieldNames(blob), (std::vector<std::string>{"x", "y", "z", "intensity"}));

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
    EXPECT_LT(max_range, 130.0f); // HDL-64E range: meters, little-endian floats

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
  EXPECT_EQ(fieldNames(blob), (std::vector<std::string>{"x", "y", "z", "intensity"}));

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
    EXPECT_EQ(fieldNames(blob), (std::vector<std::string>{"x", "y", "z"}));

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
    EXPECT_GT(extent, 0.1f); // the bunny is about 0.15 m: meters, not millimeters
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
  EXPECT_TRUE(hasField(blob, "normal_x") && hasField(blob, "normal_z"));
  EXPECT_TRUE(hasXYZ(blob));
  EXPECT_FALSE(hasField(blob, "intensity"));
  EXPECT_TRUE(hasField(blob, "curvature"));

  pcl::PointCloud<pcl::PointNormal> normals;
  ASSERT_TRUE(loadCloud(dataPath(bun0), normals, &error)) << error;
  ASSERT_EQ(normals.size(), 397u);
  EXPECT_NEAR(normals[0].getNormalVector3fMap().norm(), 1.0f, 1e-3f);
  EXPECT_FLOAT_EQ(normals[0].x, 0.0054215998f);

  pcl::PCLPointCloud2 old_version; // "VERSION .5", no VIEWPOINT
  ASSERT_TRUE(loadCloud(dataPath(bun4), old_version, &error)) << error;
  EXPECT_EQ(old_version.width * old_version.height, 361u);
  EXPECT_FALSE(hasField(old_version, "normal_x"));
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
    EXPECT_FALSE(hasField(blob, "rgb"));
    EXPECT_TRUE(hasField(blob, "rgba"));
    EXPECT_FALSE(hasField(blob, "intensity"));

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
    std::size_t same_color = 0, colored = 0;
    for (std::size_t i = 0; i < rgb.size(); i += 97) {
      same_color += (rgb[i].rgba & 0xFFFFFFu) == (rgba[i].rgba & 0xFFFFFFu);
      colored += (rgba[i].rgba & 0xFFFFFFu) != 0;
    }
    EXPECT_EQ(same_color, (rgb.size() + 96) / 97);
    EXPECT_GT(colored, 0u);
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
       fs::recursive_directory_iterator(pcl::phaser::test::dataDir())) {
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

  if (pcl::phaser::test::haveData("object/stanford_bunny/T_bun000_bun045.txt")) {
    Eigen::Matrix4d bunny;
    ASSERT_TRUE(loadTransform(dataPath("object/stanford_bunny/T_bun000_bun045.txt"),
                              bunny, &error))
        << error;
    EXPECT_NEAR(rotationAngleDeg(bunny), 34.3, 0.1);
    EXPECT_NEAR((bunny.topRightCorner<3, 1>().norm()), 0.053, 0.001);
  }
  const std::string kitti =
      "lidar/kitti_synthetic_gt/T_cloud050_cloud049_procrustes.txt";
  if (pcl::phaser::test::haveData(kitti)) {
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
  EXPECT_EQ(pcl::phaser::test::dataDir(), dir);
  EXPECT_TRUE(pcl::phaser::test::haveData("sub/a.txt"));
  EXPECT_FALSE(pcl::phaser::test::haveData("sub/missing.txt"));
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

/* =============================== bad input ===================================== */
