/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The reader process (io/cloud_reading.h): clouds read through it equal those read
 * directly, a file that makes PCL's reader fail is a clean error through it too, and
 * when it is killed loadCloud() reads by itself again.
 */
#include "cloud_reading.h"

#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>

namespace {

std::string folder()
{
  char name[] = "/tmp/pcl_phaser_reader_XXXXXX";
  return ::mkdtemp(name) ? name : "/tmp";
}

} // namespace

TEST(CloudReaderProcess, ReadsAsTheCallerWouldAndFallsBackWhenKilled)
{
  const std::string dir = folder();
  pcl::PointCloud<pcl::PointXYZI> cloud; // organized, 10 rows of 100: rows must not mix
  for (int i = 0; i < 1000; ++i) {
    pcl::PointXYZI p;
    p.x = 0.01f * static_cast<float>(i);
    p.y = -0.5f * p.x;
    p.z = 1.0f;
    p.intensity = static_cast<float>(i % 7);
    cloud.push_back(p);
  }
  cloud.width = 100;
  cloud.height = 10;
  ASSERT_EQ(pcl::io::savePCDFileBinary(dir + "/c.pcd", cloud), 0);
  std::ofstream(dir + "/bad.pcd") << "VERSION .7\nFIELDS x y z\nSIZE 4 4\nWIDTH 9\n";

  pcl::PointCloud<pcl::PointXYZI> direct, through, after;
  std::string error;
  ASSERT_TRUE(pcl::phaser::loadCloud(dir + "/c.pcd", direct, &error)) << error;
  ASSERT_TRUE(pcl::phaser::startCloudReader());
  const pid_t pid = pcl::phaser::cloudReaderPid();
  ASSERT_GT(pid, 0);
  EXPECT_TRUE(pcl::phaser::startCloudReader()); // idempotent
  EXPECT_EQ(pcl::phaser::cloudReaderPid(), pid);
  ASSERT_TRUE(pcl::phaser::loadCloud(dir + "/c.pcd", through, &error)) << error;
  ASSERT_EQ(through.size(), direct.size());
  EXPECT_EQ(through.height, 10u);
  for (std::size_t i = 0; i < direct.size(); ++i) {
    EXPECT_EQ(through[i].x, 0.01f * static_cast<float>(i));
    EXPECT_EQ(through[i].x, direct[i].x);
    EXPECT_EQ(through[i].intensity, direct[i].intensity);
  }
  EXPECT_FALSE(pcl::phaser::loadCloud(dir + "/bad.pcd", through, &error));
  EXPECT_NE(error.find("bad.pcd"), std::string::npos) << error;
  EXPECT_EQ(pcl::phaser::cloudReaderPid(), pid); // a bad file does not stop it
  // uchar blue before red: PCL's PLY reader aborts, a clean error through the reader
  // too.
  std::ofstream(dir + "/abort.ply")
      << "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
         "property float z\nproperty uchar blue\nproperty uchar green\n"
         "property uchar red\nend_header\n1 2 3 4 5 6\n6 7 8 9 10 11\n";
  EXPECT_FALSE(pcl::phaser::loadCloud(dir + "/abort.ply", through, &error));
  EXPECT_NE(error.find("abort.ply': PCL's PLY reader crashed"), std::string::npos)
      << error;
  EXPECT_EQ(pcl::phaser::cloudReaderPid(), pid);

  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  ASSERT_TRUE(pcl::phaser::loadCloud(dir + "/c.pcd", after, &error)) << error;
  EXPECT_EQ(after.size(), direct.size());
  EXPECT_EQ(pcl::phaser::cloudReaderPid(), -1);
  std::filesystem::remove_all(dir);
}
