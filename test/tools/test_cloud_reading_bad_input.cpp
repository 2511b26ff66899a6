/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Cloud reading on bad input: missing, unreadable, garbage and lying files.
 */
#include "cloud_reading_test_support.h"

using namespace pcl::phaser::test;

namespace {

/** Whether a load error reports the expected outcome. Under AddressSanitizer its
 *  allocator aborts where a plain build throws bad_alloc ("ran out of memory"). */
bool hasOutcome(const std::string& error, const std::string& expected)
{
  if (error.find(expected) != std::string::npos)
    return (true);
#if defined(__SANITIZE_ADDRESS__)
  return (expected == "ran out of memory" &&
          error.find("crashed") != std::string::npos);
#else
  return (false);
#endif
}

/** Writes each (name, bytes, expected outcome) file and loads it: the load fails with
 *  the outcome in a message naming the file, or, where the outcome is empty (PCL 1.13.0
 *  reads the file, with zeros or shuffled values), the invariants of a load hold. */
void checkHostileFiles(
    const TempDir& tmp,
    const std::vector<std::tuple<std::string, std::string, std::string>>& cases)
{
  for (const auto& [name, bytes, expected] : cases) {
    writeFile(tmp.file(name), bytes);
    if (expected.empty()) {
      loadAndCheckInvariants(tmp.file(name), name);
      continue;
    }
    pcl::PCLPointCloud2 blob;
    std::string error;
    EXPECT_FALSE(loadCloud(tmp.file(name), blob, &error)) << name;
    EXPECT_TRUE(hasOutcome(error, expected)) << name << ": " << error;
    EXPECT_NE(error.find(name), std::string::npos) << error;
  }
}

} // namespace

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
       "ran out of memory"},
      {"points_2pow32.pcd",
       pcdHeader(xyz, f4, fff, ones, "4294967296", "1", "4294967296", "binary") +
           twelve,
       "rejected"},
      {"wh_overflow.pcd",
       pcdHeader(xyz, f4, fff, ones, "4294967296", "4294967296", "0", "binary"),
       "rejected"},
      {"truncated_binary.pcd", xyzPcdHeader("1000", "binary") + "abc", "rejected"},
      {"truncated_compressed.pcd",
       xyzPcdHeader("1000", "binary_compressed") + "abcdefghijklmnop", "rejected"},
      {"compressed_size_block_missing.pcd",
       xyzPcdHeader("1000", "binary_compressed") + "abc", "rejected"},
      {"compressed_claims_2GB.pcd",
       xyzPcdHeader("1000", "binary_compressed") +
           bytesOf(std::vector<std::uint32_t>{0x7fffffffu, 0x7fffffffu}) + "abcdefgh",
       "rejected"},
      {"compressed_wrong_size.pcd",
       xyzPcdHeader("1000", "binary_compressed") +
           bytesOf(std::vector<std::uint32_t>{4, 999}) + "abcd",
       "rejected"},
      {"compressed_ratio.pcd",
       xyzPcdHeader("100000000", "binary_compressed") +
           bytesOf(std::vector<std::uint32_t>{4, 1200000000u}) + "abcd",
       "ran out of memory"},
  };
  checkHostileFiles(tmp, cases);
}

TEST(CloudIoBadInput, PcdFieldsThatLie)
{
  TempDir tmp;
  QuietPcl quiet;
  const std::string twelve = randomBytes(12, 3);
  const std::string xyz = "x y z", f4 = "4 4 4", fff = "F F F", ones = "1 1 1";
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"ascii_claims_more.pcd", xyzPcdHeader("1000000", "ascii") + "1 2 3\n",
       "rejected"},
      {"short_ascii.pcd", xyzPcdHeader("3", "ascii") + "1 2 3\n4 5\n", "rejected"},
      {"wh_mismatch.pcd", pcdHeader(xyz, f4, fff, ones, "10", "10", "50", "ascii"),
       "rejected"},
      {"size_mismatch.pcd", pcdHeader(xyz, "4 4", fff, ones, "1", "1", "1", "ascii"),
       "rejected"},
      {"bad_type.pcd", pcdHeader(xyz, f4, "F F Q", ones, "1", "1", "1", "ascii"),
       "rejected"},
      {"float16.pcd",
       pcdHeader(xyz, "2 2 2", fff, ones, "1", "1", "1", "binary") + "123456",
       "inconsistent"},
      {"count_zero.pcd", pcdHeader(xyz, f4, fff, "0 1 1", "1", "1", "1", "ascii"),
       "rejected"},
      {"negative_points.pcd", xyzPcdHeader("-1", "binary") + twelve, "threw"},
      {"no_data_type.pcd",
       "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nPOINTS 1\nDATA\n",
       "threw"},
      {"no_data_line.pcd",
       "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nPOINTS 1\n", ""},
      {"no_fields.pcd", "VERSION 0.7\nWIDTH 1\nPOINTS 1\nDATA ascii\n1 2 3\n",
       "rejected"},
      {"unknown_data.pcd", xyzPcdHeader("1", "fancy") + twelve, ""},
      {"control_character.pcd",
       pcdHeader("x\vy z", f4, fff, ones, "1", "1", "1", "ascii") + "1 2 3\n",
       "rejected"},
  };
  checkHostileFiles(tmp, cases);
}

TEST(CloudIoBadInput, PlyCountsAndGridsThatLie)
{
  TempDir tmp;
  QuietPcl quiet;
  const std::string ascii = "ascii", binary = "binary_little_endian";
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      // PCL would allocate and zero 12 GB for this one.
      {"vertices_1e9.ply", plyXYZ(binary, "1000000000") + "abc", "ran out of memory"},
      {"vertices_5e9.ply", plyXYZ(binary, "5000000000") + "abc", "ran out of memory"},
      {"short_ascii.ply", plyXYZ(ascii, "3") + "1 2 3\n", "rejected"},
      // More vertices than the obj_info grid: PCL would assert (abort).
      {"grid_too_small.ply", plyXYZ(ascii, "2", gridInfo("1", "1")) + "1 2 3\n4 5 6\n",
       "crashed (Aborted)"},
      {"grid_huge.ply",
       plyXYZ(ascii, "1", gridInfo("100000", "100000"), rangeGrid("1")) +
           "1 2 3\n1 0\n",
       "ran out of memory"},
      {"grid_negative.ply", plyXYZ(ascii, "1", gridInfo("-5", "2")) + "1 2 3\n",
       "ran out of memory"},
      {"grid_without_range_grid.ply",
       plyXYZ(ascii, "1", gridInfo("2", "2")) + "1 2 3\n", ""},
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
      // ... and this one wraps to offset 8: PCL silently copies the wrong bytes (the
      // range-grid check of io/reader_child.cpp).
      {"range_grid_index_wraps_silently.ply",
       plyXYZ(ascii, "2", gridInfo("2", "2"), rangeGrid("4")) +
           "1 2 3\n4 5 6\n1 357913942\n0\n0\n1 0\n",
       "index 357913942 is outside"},
      {"range_grid_binary_bad_index.ply",
       plyXYZ(binary, "1", gridInfo("2", "1"), rangeGrid("2")) +
           bytesOf(std::vector<float>{1, 2, 3}) + std::string("\x01\x05\0\0\0\0", 6),
       "index 5 is outside"},
      {"range_grid_extra_values.ply",
       plyXYZ(ascii, "1", gridInfo("2", "1"), rangeGrid("2")) + "1 2 3\n1 0 7\n0\n",
       "rejected"},
      {"range_grid_without_dims.ply",
       plyXYZ(ascii, "1", "", rangeGrid("2")) + "1 2 3\n1 0\n0\n", "inconsistent"},
  };
  checkHostileFiles(tmp, cases);
}

TEST(CloudIoBadInput, PlyHeadersThatLie)
{
  TempDir tmp;
  QuietPcl quiet;
  const std::string ascii = "ascii", binary = "binary_little_endian";
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      // PCL's obj_info handler asserts (aborts) on an indented obj_info line.
      {"indented_obj_info.ply",
       plyXYZ(ascii, "1", " obj_info num_cols 2\n") + "1 2 3\n", "crashed (Aborted)"},
      // uchar blue before red: PCL writes the packed rgb past the buffer (abort).
      {"blue_before_red.ply",
       plyXYZ(ascii, "2", "",
              "property uchar blue\nproperty uchar green\nproperty uchar red\n") +
           "1 2 3 4 5 6\n6 7 8 9 10 11\n",
       "crashed (Aborted)"},
      {"blue_without_red.ply",
       plyXYZ(ascii, "2", "", "property uchar green\nproperty uchar blue\n") +
           "1 2 3 4 5\n6 7 8 9 10\n",
       ""},
      // PCL sizes list fields from the first vertex only: lists are not supported.
      {"vertex_list.ply",
       plyXYZ(ascii, "2", "", "property list uchar float extra\n") +
           "1 2 3 1 9\n4 5 6 3 9 9 9\n",
       ""},
      {"no_end_header.ply", "ply\nformat ascii 1.0\nelement vertex 1\n", "rejected"},
      {"no_format.ply", "ply\nelement vertex 1\nend_header\n1 2 3\n", "rejected"},
      {"bad_format.ply", "ply\nformat utf8 1.0\nelement vertex 0\nend_header\n",
       "rejected"},
      {"bad_type.ply", plyXYZ(ascii, "1", "", "property quad w\n") + "1 2 3 4\n",
       "rejected"},
      {"bad_count.ply", plyXYZ(ascii, "-1") + "1 2 3\n", "ran out of memory"},
      {"two_vertex_elements.ply",
       plyXYZ(ascii, "1", "", "element vertex 1\nproperty float x\n") + "1 2 3\n1\n",
       "rejected"},
  };
  checkHostileFiles(tmp, cases);
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
