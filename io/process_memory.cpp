/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "process_memory.h"

#include <cstdint>
#include <cstdlib>
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

namespace pcl {
namespace phaser {

void preferHugePages()
{
  constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
  constexpr int kStep = 256 << 20;
  // One arena (the sbrk heap), blocks up to 32 MiB (glibc's largest threshold) from
  // it, grown kStep at a time and never trimmed.
  if (!mallopt(M_ARENA_MAX, 1) || !mallopt(M_MMAP_THRESHOLD, 32 << 20) ||
      !mallopt(M_TOP_PAD, kStep) || !mallopt(M_TRIM_THRESHOLD, 4 * kStep))
    return;
  void* const failed = reinterpret_cast<void*>(-1); // sbrk's error value
  void* const first = sbrk(0);
  // More than the free heap of a process just started (PCL's and VTK's static
  // objects leave about 1 MiB), so the heap grows by kStep: only address space.
  // volatile: the compiler may drop a malloc whose block is never used.
  void* volatile probe = std::malloc(16 << 20);
  std::free(probe);
  void* const last = sbrk(0);
  const auto begin = reinterpret_cast<std::uintptr_t>(first);
  const auto end = reinterpret_cast<std::uintptr_t>(last);
  const std::uintptr_t start = (begin + kHugePage - 1) & ~(kHugePage - 1);
  if (first != failed && last != failed && end > start)
    madvise(reinterpret_cast<void*>(start), end - start, MADV_HUGEPAGE);
}

} // namespace phaser
} // namespace pcl
