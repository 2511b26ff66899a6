/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <cstddef>

namespace pcl::phaser {
namespace detail {

/** \brief Large FFTW buffers freed by bufferRelease are kept and handed out again by
 *  bufferAcquire of the same size, so the dozen 3-D correlations of an align do not
 *  each fault in fresh pages (on the bunny views the kernel's page faults took as long
 *  as the FFTs): up to 256 MB while a scope lives (in any thread), 128 MB between
 *  aligns (the oldest are freed when the last scope ends), about what malloc's heap
 *  keeps for the next align without the pool. */
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

/** \brief Returns \a p (from bufferAcquire(\a bytes)): kept while the pool holds less
 *  than its budget, else fftw_free. */
void bufferRelease(void* p, std::size_t bytes) noexcept;

} // namespace detail
} // namespace pcl::phaser
