/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * preferHugePages() (io/process_memory.h): after it, a block the engine would take
 * (below 32 MiB) is faulted in transparent huge pages. Each test runs in a process of
 * its own (gtest_discover_tests), so the process-wide malloc settings stay here.
 */
#include "process_memory.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <memory>
#include <string>

namespace {

/** AnonHugePages of this process, kB. */
long anonHugePagesKb()
{
  std::ifstream in("/proc/self/smaps_rollup");
  in.ignore(1 << 10, '\n'); // the address range
  for (std::string key; in >> key;) {
    long kb = 0;
    in >> kb;
    if (key == "AnonHugePages:")
      return kb;
    in.ignore(1 << 10, '\n');
  }
  return -1;
}

} // namespace

TEST(ProcessMemory, HeapBlocksAreFaultedInHugePages)
{
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "the sanitizer's allocator, not glibc's, serves malloc";
#endif
  std::ifstream mode_file("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string mode;
  std::getline(mode_file, mode);
  if (mode.empty() || mode.find("[never]") != std::string::npos || anonHugePagesKb() < 0)
    GTEST_SKIP() << "this kernel gives no transparent huge pages (" << mode << ")";
  const long before = anonHugePagesKb();
  pcl::phaser::preferHugePages();
  constexpr std::size_t kBytes = std::size_t(24) << 20; // a 128^3-grid buffer is 16 MiB
  const std::unique_ptr<char[]> block(new char[kBytes]);
  std::memset(block.get(), 1, kBytes);
  // At least half the block in 2 MiB pages (its ends may share 4 KiB-paged areas).
  EXPECT_GE(anonHugePagesKb() - before, static_cast<long>(kBytes / 2 / 1024))
      << "transparent huge pages: " << mode;
  EXPECT_EQ(block[kBytes - 1], 1);
}
