/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace pcl::phaser {
namespace test {

/** \brief The shared real-data directory: the environment variable PCL_PHASER_DATA if
 * set and non-empty, else the compile definition PCL_PHASER_DATA_DIR, else "".
 * \return the directory (it may not exist)
 */
inline std::string dataDir()
{
  const char* env = std::getenv("PCL_PHASER_DATA");
  if (env && *env)
    return (env);
#ifdef PCL_PHASER_DATA_DIR
  return (PCL_PHASER_DATA_DIR);
#else
  return ("");
#endif
}

/** \brief Full path of a file of the shared data.
 * \param[in] relative path inside the data directory, e.g. "pcl/bun0.pcd"
 * \return dataDir() / relative, lexically normalized
 */
inline std::string dataPath(const std::string& relative)
{
  return ((std::filesystem::path(dataDir()) / relative).lexically_normal().string());
}

/** \brief Whether a file (or folder) of the shared data is present.
 * \param[in] relative path inside the data directory
 * \return true if dataPath(relative) exists
 */
inline bool haveData(const std::string& relative)
{
  std::error_code ec;
  return (!dataDir().empty() && std::filesystem::exists(dataPath(relative), ec));
}

} // namespace test
} // namespace pcl::phaser

/** \brief Skip the current test (GTEST_SKIP, so only in a test body or fixture
 * SetUp) with a message naming the missing file when the shared data lacks it.
 * Use once per needed file: PCL_PHASER_REQUIRE_DATA("pcl/bun0.pcd");
 */
#define PCL_PHASER_REQUIRE_DATA(relative)                                              \
  do {                                                                                 \
    if (!::pcl::phaser::test::haveData(relative))                                      \
      GTEST_SKIP() << "shared test data not found: "                                   \
                   << ::pcl::phaser::test::dataPath(relative)                          \
                   << " (set PCL_PHASER_DATA to the shared data directory)";           \
  } while (false)
