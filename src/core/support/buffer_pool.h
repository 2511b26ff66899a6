/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <cstddef>

namespace pcl::phaser {
namespace detail {

/** \brief While one lives (in any thread), large FFTW buffers freed by
 *  bufferRelease are kept and handed out again by bufferAcquire of the same size, so
 *  the dozen 3-D correlations of an align do not each fault in fresh pages (on the
 *  bunny views the kernel's page faults took as long as the FFTs). The last one to end
 *  frees what was kept: nothing is held between aligns. */
class BufferPoolScope {
public:
  BufferPoolScope();
  ~BufferPoolScope();
  BufferPoolScope(const BufferPoolScope&) = delete;
  BufferPoolScope& operator=(const BufferPoolScope&) = delete;
};

/** \brief fftw_malloc(\a bytes), or a kept buffer of that size. \throws std::bad_alloc
 */
void* bufferAcquire(std::size_t bytes);

/** \brief Returns \a p (from bufferAcquire(\a bytes)): kept while a BufferPoolScope
 *  lives and the pool holds less than its budget, else fftw_free. */
void bufferRelease(void* p, std::size_t bytes) noexcept;

} // namespace detail
} // namespace pcl::phaser
