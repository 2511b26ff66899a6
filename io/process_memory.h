/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
/** \file process_memory.h
 * \brief How the tools' processes take memory from the system (not installed). */
#pragma once

namespace pcl {
namespace phaser {

/** \brief Let a short-lived tool process fault its heap in 2 MiB transparent huge
 * pages.
 *
 * One align in a fresh process first-touches about 80 MB, in 4 KiB faults that cost
 * about 10 us each on a virtual machine: 20k faults, a third of `pcl_phaser_align`'s
 * time beyond the align (doc/benchmarks.md, *One align per process*). This sets glibc
 * to serve blocks below 32 MiB from one arena whose heap grows in steps of 256 MiB of
 * address space (touched pages only become memory), never handed back, and advises
 * that heap (MADV_HUGEPAGE) as glibc's `glibc.malloc.hugetlb=1` tunable would. Call
 * it first in main(), before threads start. Advice only: where the kernel has no
 * transparent huge pages, or another allocator runs (sanitizers), nothing changes.
 * Library users keep their process's settings: the library never calls it. */
void preferHugePages();

} // namespace phaser
} // namespace pcl
