/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <fftw3.h>

#include <cstddef>
#include <memory>
#include <mutex>
#include <new>

namespace pcl::phaser {
namespace detail {

/** \brief The one mutex that guards every FFTW planner call in the process (planning is
 *  not thread-safe; executing an existing plan with the new-array interface is). */
inline std::mutex& fftwPlannerMutex()
{
  static std::mutex mutex;
  return mutex;
}

/** \brief Planner flags used everywhere: FFTW_ESTIMATE picks the same algorithm in
 * every run, so results are reproducible across processes (FFTW_MEASURE is not). */
constexpr unsigned kFftwFlags = FFTW_ESTIMATE;

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};

template <typename T>
using FftwBuffer = std::unique_ptr<T[], FftwFree>;

/** \brief SIMD-aligned uninitialized buffer of \a n elements. \throws std::bad_alloc */
template <typename T>
FftwBuffer<T> fftwAllocate(std::size_t n)
{
  void* p = fftw_malloc(sizeof(T) * (n ? n : 1));
  if (!p)
    throw std::bad_alloc();
  return FftwBuffer<T>(static_cast<T*>(p));
}

/** \brief Owns an fftw_plan; destroys it under the planner mutex. */
class FftwPlan {
public:
  FftwPlan() = default;
  explicit FftwPlan(fftw_plan p)
      : plan_(p)
  {
  }
  FftwPlan(FftwPlan&& o) noexcept
      : plan_(o.plan_)
  {
    o.plan_ = nullptr;
  }
  FftwPlan& operator=(FftwPlan&& o) noexcept
  {
    std::swap(plan_, o.plan_);
    return *this;
  }
  FftwPlan(const FftwPlan&) = delete;
  FftwPlan& operator=(const FftwPlan&) = delete;
  ~FftwPlan()
  {
    if (plan_) {
      std::lock_guard<std::mutex> lock(fftwPlannerMutex());
      fftw_destroy_plan(plan_);
    }
  }
  fftw_plan get() const { return plan_; }
  explicit operator bool() const { return plan_ != nullptr; }

private:
  fftw_plan plan_ = nullptr;
};

} // namespace detail
} // namespace pcl::phaser
