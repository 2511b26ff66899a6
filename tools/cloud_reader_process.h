/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * A reader process started once, so that a long-running tool never forks again.
 */
#pragma once

#include <sys/types.h>

namespace pcl {
namespace phaser {

/** \brief Start a small process that reads .pcd and .ply files for loadCloud(), each
 *  in a child of its own as before (so a crash of PCL's reader stays a clean error).
 *  Call it first in a program that reads many files while it computes
 *  (pcl_phaser_batch): a fork of a process holding hundreds of megabytes of working
 *  memory makes its later writes fault page by page (copy-on-write: about 22k faults
 *  and 10 % of the wall time per revisit pair in the batch); the reader forks from its
 *  own few megabytes instead. Without it, or if it dies, loadCloud() forks from the
 *  caller as before. Call it from the main thread before any other thread starts (the
 *  reader dies with the thread that forked it); idempotent. \return false if it could
 *  not start */
bool startCloudReader();

/** \brief The reader process, or -1 when none runs (for tests). */
pid_t cloudReaderPid();

} // namespace phaser
} // namespace pcl
