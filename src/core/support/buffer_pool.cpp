/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "support/buffer_pool.h"

#include <fftw3.h>

#include <mutex>
#include <new>
#include <utility>
#include <vector>

namespace pcl::phaser {
namespace detail {
namespace {

/** Smallest buffer kept: below it malloc reuses memory without faults. */
constexpr std::size_t kMinKeptBytes = std::size_t(1) << 20;
/** Most bytes kept: two threads' correlations at a 128^3 grid need about six buffers
 *  of 16-17 MB. */
constexpr std::size_t kMaxKeptBytes = std::size_t(256) << 20;

struct Pool {
  std::mutex mutex;
  int scopes = 0;
  std::size_t kept_bytes = 0;
  std::vector<std::pair<void*, std::size_t>> kept;

  /** Frees every kept buffer (the lock held). */
  void clear()
  {
    for (const auto& buffer : kept)
      fftw_free(buffer.first);
    kept.clear();
    kept_bytes = 0;
  }
};

Pool& pool()
{
  static Pool instance;
  return instance;
}

} // namespace

BufferPoolScope::BufferPoolScope()
{
  Pool& p = pool();
  std::lock_guard<std::mutex> lock(p.mutex);
  ++p.scopes;
}

BufferPoolScope::~BufferPoolScope()
{
  Pool& p = pool();
  std::lock_guard<std::mutex> lock(p.mutex);
  if (--p.scopes == 0)
    p.clear();
}

void* bufferAcquire(std::size_t bytes)
{
  if (bytes >= kMinKeptBytes) {
    Pool& p = pool();
    std::lock_guard<std::mutex> lock(p.mutex);
    for (std::size_t k = 0; k < p.kept.size(); ++k)
      if (p.kept[k].second == bytes) {
        void* buffer = p.kept[k].first;
        p.kept.erase(p.kept.begin() + static_cast<std::ptrdiff_t>(k));
        p.kept_bytes -= bytes;
        return buffer;
      }
  }
  void* buffer = fftw_malloc(bytes ? bytes : 1);
  if (!buffer)
    throw std::bad_alloc();
  return buffer;
}

void bufferRelease(void* buffer, std::size_t bytes) noexcept
{
  if (!buffer)
    return;
  if (bytes >= kMinKeptBytes) {
    Pool& p = pool();
    std::lock_guard<std::mutex> lock(p.mutex);
    if (p.scopes > 0 && p.kept_bytes + bytes <= kMaxKeptBytes) {
      try {
        p.kept.emplace_back(buffer, bytes);
        p.kept_bytes += bytes;
        return;
      } catch (const std::bad_alloc&) { // no room to note it: free it below
      }
    }
  }
  fftw_free(buffer);
}

} // namespace detail
} // namespace pcl::phaser
