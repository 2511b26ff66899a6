/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The engine's buffer reuse (src/core/support/buffer_pool.h): within a scope a released
 * large buffer is handed out again for its size only, scopes nest, and concurrent use
 * neither loses nor double-frees a buffer (the sanitizer pass checks the latter).
 */
#include "support/buffer_pool.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <thread>
#include <vector>

using pcl::phaser::detail::bufferAcquire;
using pcl::phaser::detail::BufferPoolScope;
using pcl::phaser::detail::bufferRelease;

namespace {

constexpr std::size_t kLarge = std::size_t(4) << 20;

TEST(BufferPool, ReleasedBufferIsReusedForItsSizeOnlyWithinAScope)
{
  const BufferPoolScope scope;
  void* first = bufferAcquire(kLarge);
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(first) % 16, 0u)
      << "FFTW's SIMD alignment";
  std::memset(first, 1, kLarge);
  bufferRelease(first, kLarge);
  void* other_size = bufferAcquire(kLarge + 4096);
  EXPECT_NE(other_size, first);
  void* same_size = bufferAcquire(kLarge);
  EXPECT_EQ(same_size, first);
  bufferRelease(same_size, kLarge);
  bufferRelease(other_size, kLarge + 4096);
}

TEST(BufferPool, BuffersOfHugePageSizeStartOnAHugePageAndSmallOnesStillWork)
{
  constexpr std::size_t kHugePage = std::size_t(2) << 20;
  // Sizes that are not whole huge pages: the last page is rounded up, not overrun.
  for (const std::size_t bytes : {kHugePage, kHugePage + 8, 3 * kHugePage + 4096}) {
    auto* p = static_cast<unsigned char*>(bufferAcquire(bytes));
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % kHugePage, 0u) << bytes;
    std::memset(p, 7, bytes);
    EXPECT_EQ(p[bytes - 1], 7);
    bufferRelease(p, bytes);
  }
  for (const std::size_t bytes : {std::size_t(0), std::size_t(24), kHugePage - 8}) {
    auto* p = static_cast<unsigned char*>(bufferAcquire(bytes));
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % 16, 0u) << bytes;
    std::memset(p, 7, bytes);
    bufferRelease(p, bytes);
  }
}

TEST(BufferPool, AnInnerScopeEndingKeepsTheOuterScopesBuffers)
{
  const BufferPoolScope outer;
  void* buffer = bufferAcquire(kLarge);
  {
    const BufferPoolScope inner;
    bufferRelease(buffer, kLarge);
  }
  void* again = bufferAcquire(kLarge);
  EXPECT_EQ(again, buffer);
  bufferRelease(again, kLarge);
}

TEST(BufferPool, ConcurrentAcquireAndReleaseHandOutEachBufferOnce)
{
  const BufferPoolScope scope;
  constexpr int kRounds = 50;
  const auto work = [](unsigned char mark) {
    for (int round = 0; round < kRounds; ++round) {
      auto* p = static_cast<unsigned char*>(bufferAcquire(kLarge));
      std::memset(p, mark, kLarge);
      std::this_thread::yield();
      // Another thread holding the same buffer would have overwritten the marks.
      EXPECT_EQ(p[0], mark);
      EXPECT_EQ(p[kLarge - 1], mark);
      bufferRelease(p, kLarge);
    }
  };
  std::thread a(work, 1), b(work, 2);
  a.join();
  b.join();
}

TEST(BufferPool, WorksWithoutAScopeAndForEmptyBuffers)
{
  void* p = bufferAcquire(kLarge);
  ASSERT_NE(p, nullptr);
  bufferRelease(p, kLarge); // kept for the next align, or freed
  void* empty = bufferAcquire(0);
  ASSERT_NE(empty, nullptr);
  bufferRelease(empty, 0);
  bufferRelease(nullptr, kLarge);
}

} // namespace
