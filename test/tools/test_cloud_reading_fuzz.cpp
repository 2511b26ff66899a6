/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Cloud reading robustness sweeps: truncations, random byte changes, header numbers.
 * Each load forks a reader (a few ms), so a header is cut at every 3rd byte and a body
 * at every 11th.
 */
#include "cloud_reading_test_support.h"

using namespace pcl::phaser::test;

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
  // Color and normals: PCL packs uchar red/green/blue(/alpha) into rgb(a).
  pcl::PointCloud<pcl::PointXYZRGBNormal> color;
  for (int i = 0; i < 8; ++i) {
    pcl::PointXYZRGBNormal p;
    p.x = static_cast<float>(i);
    p.y = 2.0f * static_cast<float>(i);
    p.z = -1.0f;
    p.r = static_cast<std::uint8_t>(30 * i);
    p.g = 7;
    p.b = 200;
    p.normal_x = 1.0f;
    color.push_back(p);
  }
  pcl::io::savePLYFileBinary(tmp.file("color_binary.ply"), color);
  add("color_binary.ply");
  pcl::io::savePLYFileASCII(tmp.file("color_ascii.ply"), color);
  add("color_ascii.ply");
  pcl::io::savePCDFileBinaryCompressed(tmp.file("color.pcd"), color);
  add("color.pcd");
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
    std::size_t header_end = bytes.find("DATA "); // PCD
    if (header_end == std::string::npos)
      header_end = bytes.find("end_header"); // PLY
    const std::size_t header_bytes =
        header_end == std::string::npos ? 64 : header_end + 32;
    for (std::size_t size = 0; size < bytes.size();
         size += size < header_bytes ? 3 : 11) {
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
    for (int trial = 0; trial < 100; ++trial) {
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
