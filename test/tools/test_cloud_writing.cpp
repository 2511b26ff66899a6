/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * saveCloud: round trips of every format and field layout, and its errors.
 */
#include "cloud_reading_test_support.h"

using namespace pcl::phaser::test;

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
 *  representable value that differs from point to point (color alpha 255). */
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
    EXPECT_TRUE(hasXYZ(blob)) << what;
    EXPECT_TRUE(hasField(blob, "normal_x") && hasField(blob, "normal_z")) << what;
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
