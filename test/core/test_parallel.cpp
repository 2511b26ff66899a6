/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The engine's work sharing (src/core/parallel.h): every index once, slots unique among
 * the threads at work, exceptions passed on after the chunks in flight, nested and
 * concurrent calls. (That a parked worker does not hold the caller up is a property of
 * the timing; doc/benchmarks.md, *Threads, a busy core, the gravity prior, Python*, measures it with a busy
 * core.)
 */
#include "support/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using pcl::phaser::detail::parallelFor;

namespace {

/** How often parallelFor(count, chunk, threads) visits each index. */
std::vector<int> visits(std::ptrdiff_t count, std::ptrdiff_t chunk, int threads)
{
  std::vector<std::atomic<int>> seen(
      static_cast<std::size_t>(std::max<std::ptrdiff_t>(count, 0)));
  parallelFor(count, chunk, threads,
              [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
                EXPECT_LE(last - first, std::max<std::ptrdiff_t>(chunk, 1));
                for (std::ptrdiff_t i = first; i < last; ++i)
                  ++seen[static_cast<std::size_t>(i)];
              });
  std::vector<int> out;
  for (const std::atomic<int>& s : seen)
    out.push_back(s.load());
  return out;
}

} // namespace

TEST(ParallelFor, VisitsEveryIndexOnce)
{
  for (int threads : {0, 1, 2, 4, 16})
    for (std::ptrdiff_t count : {0, 1, 7, 64, 1000})
      for (std::ptrdiff_t chunk : {0, 1, 3, 64, 5000}) {
        const std::vector<int> v = visits(count, chunk, threads);
        ASSERT_EQ(v.size(), static_cast<std::size_t>(count));
        for (std::size_t i = 0; i < v.size(); ++i)
          ASSERT_EQ(v[i], 1) << "index " << i << ", count " << count << ", chunk "
                             << chunk << ", threads " << threads;
      }
}

TEST(ParallelFor, SlotsAreDistinctAmongThreadsAtWork)
{
  const int threads = 4;
  std::vector<std::atomic<int>> busy(threads);
  std::atomic<int> clashes{0}, out_of_range{0};
  parallelFor(400, 1, threads, [&](std::ptrdiff_t, std::ptrdiff_t, int slot) {
    if (slot < 0 || slot >= threads) {
      ++out_of_range;
      return;
    }
    if (busy[static_cast<std::size_t>(slot)].fetch_add(1) != 0)
      ++clashes;
    std::this_thread::sleep_for(std::chrono::microseconds(50));
    --busy[static_cast<std::size_t>(slot)];
  });
  EXPECT_EQ(out_of_range.load(), 0);
  EXPECT_EQ(clashes.load(), 0);
}

TEST(ParallelFor, PassesTheFirstExceptionOnAfterTheOtherChunks)
{
  for (int threads : {1, 2, 4}) {
    std::atomic<int> running{0}, after_return{0};
    bool thrown = false;
    try {
      parallelFor(100, 1, threads, [&](std::ptrdiff_t first, std::ptrdiff_t, int) {
        ++running;
        std::this_thread::sleep_for(std::chrono::microseconds(100));
        --running;
        if (first == 10)
          throw std::runtime_error("chunk 10");
      });
    } catch (const std::runtime_error& e) {
      thrown = std::string(e.what()) == "chunk 10";
      after_return = running.load(); // no chunk may still run once the call returned
    }
    EXPECT_TRUE(thrown) << threads << " threads";
    EXPECT_EQ(after_return.load(), 0) << threads << " threads";
  }
}

TEST(ParallelFor, NestedAndConcurrentCallsComplete)
{
  std::atomic<long> total{0};
  const auto work = [&] {
    parallelFor(8, 1, 2, [&](std::ptrdiff_t, std::ptrdiff_t, int) {
      parallelFor(100, 10, 2, [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
        total += last - first;
      });
    });
  };
  std::vector<std::thread> callers;
  for (int i = 0; i < 4; ++i)
    callers.emplace_back(work);
  for (std::thread& t : callers)
    t.join();
  EXPECT_EQ(total.load(), 4 * 8 * 100);
}
