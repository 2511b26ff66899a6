/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "support/fftw_support.h"

namespace pcl::phaser {
namespace detail {

std::mutex& fftwPlannerMutex()
{
  static std::mutex mutex;
  return mutex;
}

} // namespace detail
} // namespace pcl::phaser
