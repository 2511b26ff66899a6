/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * loadTransform / parseTransform: the T_target_source files of --gt.
 */
#include "cloud_reading_test_support.h"

using namespace pcl::phaser::test;

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
      {"1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 0", "found 17"},
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
  std::string text;
  for (Eigen::Index i = 0; i < 16; ++i) {
    char buffer[64];
    std::snprintf(buffer, sizeof(buffer), "%.17g%c", t(i / 4, i % 4),
                  i % 4 == 3 ? '\n' : ' ');
    text += buffer;
  }
  writeFile(tmp.file("t.txt"), text);
  ASSERT_TRUE(loadTransform(tmp.file("t.txt"), m, &error)) << error;
  EXPECT_EQ(m, t); // 17 significant digits read back exactly
}
