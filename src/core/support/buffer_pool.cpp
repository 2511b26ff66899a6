/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "support/buffer_pool.h"

#include <fftw3.h>

#include <cstdlib>
#include <mutex>
#include <new>
#include <sys/mman.h>
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
/** Most bytes kept once no align runs: what malloc's heap kept for the next align
 *  before (freeing them all at once made it hand the memory back, and a warm process
 *  fault it in again: 1.7k -> 9-18k minor faults a revisit). */
constexpr std::size_t kIdleKeptBytes = std::size_t(128) << 20;

/** Buffers of at least this many bytes are whole transparent huge pages: a process's
 *  first align touches ~100 MB of volumes and spectra, 4 KB a fault otherwise. */
constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

/** \a bytes rounded up to whole huge pages. */
std::size_t hugePageRounded(std::size_t bytes)
{
  return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
}

/** New memory of \a bytes, SIMD-aligned for FFTW; from kHugePageBytes on, huge-page
 *  aligned and advised to be backed by huge pages (where the kernel allows it). */
void* allocate(std::size_t bytes)
{
  if (bytes < kHugePageBytes)
    return fftw_malloc(bytes ? bytes : 1);
  void* buffer = std::aligned_alloc(kHugePageBytes, hugePageRounded(bytes));
  if (buffer)
    madvise(buffer, hugePageRounded(bytes), MADV_HUGEPAGE); // advice: failure is fine
  return buffer;
}

/** Frees what allocate(\a bytes) returned. */
void deallocate(void* buffer, std::size_t bytes) noexcept
{
  if (bytes < kHugePageBytes)
    fftw_free(buffer);
  else
    std::free(buffer);
}

struct Pool {
  std::mutex mutex;
  int scopes = 0;
  std::size_t kept_bytes = 0;
  std::vector<std::pair<void*, std::size_t>> kept;

  /** Frees the oldest kept buffers until at most \a budget bytes remain (the lock
   *  held). */
  void shrink(std::size_t budget)
  {
    std::size_t k = 0;
    for (; k < kept.size() && kept_bytes > budget; ++k) {
      deallocate(kept[k].first, kept[k].second);
      kept_bytes -= kept[k].second;
    }
    kept.erase(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(k));
  }
};

Pool& pool()
{
  // Never destroyed: an object freed at exit after it (a cached target) still returns
  // its buffers here, and what is kept stays reachable, not leaked.
  static Pool* const instance = new Pool;
  return *instance;
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
    p.shrink(kIdleKeptBytes);
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
  void* buffer = allocate(bytes);
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
    const std::size_t budget = p.scopes > 0 ? kMaxKeptBytes : kIdleKeptBytes;
    if (p.kept_bytes + bytes <= budget) {
      try {
        p.kept.emplace_back(buffer, bytes);
        p.kept_bytes += bytes;
        return;
      } catch (const std::bad_alloc&) { // no room to note it: free it below
      }
    }
  }
  deallocate(buffer, bytes);
}

} // namespace detail
} // namespace pcl::phaser
