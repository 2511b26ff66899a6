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
#include <utility>

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

/** \brief The FFTW calls of one precision: libfftw3 for double, libfftw3f for float. */
template <typename Real>
struct Fftw;

template <>
struct Fftw<double> {
  using Plan = fftw_plan;
  using Complex = fftw_complex;
  static constexpr auto plan_r2c_2d = fftw_plan_dft_r2c_2d;
  static constexpr auto plan_c2r_2d = fftw_plan_dft_c2r_2d;
  static constexpr auto plan_many_dft = fftw_plan_many_dft;
  static constexpr auto execute_r2c = fftw_execute_dft_r2c;
  static constexpr auto execute_c2r = fftw_execute_dft_c2r;
  static constexpr auto execute_dft = fftw_execute_dft;
  static constexpr auto destroy_plan = fftw_destroy_plan;
  static constexpr auto alignment_of = fftw_alignment_of;
};

template <>
struct Fftw<float> {
  using Plan = fftwf_plan;
  using Complex = fftwf_complex;
  static constexpr auto plan_r2c_2d = fftwf_plan_dft_r2c_2d;
  static constexpr auto plan_c2r_2d = fftwf_plan_dft_c2r_2d;
  static constexpr auto plan_many_dft = fftwf_plan_many_dft;
  static constexpr auto execute_r2c = fftwf_execute_dft_r2c;
  static constexpr auto execute_c2r = fftwf_execute_dft_c2r;
  static constexpr auto execute_dft = fftwf_execute_dft;
  static constexpr auto destroy_plan = fftwf_destroy_plan;
  static constexpr auto alignment_of = fftwf_alignment_of;
};

/** \brief Owns a plan of FFTW in precision \a Real; destroys it under the planner
 *  mutex (one mutex for both precisions). */
template <typename Real>
class BasicFftwPlan {
public:
  using Plan = typename Fftw<Real>::Plan;
  BasicFftwPlan() = default;
  explicit BasicFftwPlan(Plan p)
      : plan_(p)
  {
  }
  BasicFftwPlan(BasicFftwPlan&& o) noexcept
      : plan_(o.plan_)
  {
    o.plan_ = nullptr;
  }
  BasicFftwPlan& operator=(BasicFftwPlan&& o) noexcept
  {
    std::swap(plan_, o.plan_);
    return *this;
  }
  BasicFftwPlan(const BasicFftwPlan&) = delete;
  BasicFftwPlan& operator=(const BasicFftwPlan&) = delete;
  ~BasicFftwPlan()
  {
    if (plan_) {
      std::lock_guard<std::mutex> lock(fftwPlannerMutex());
      Fftw<Real>::destroy_plan(plan_);
    }
  }
  Plan get() const { return plan_; }
  explicit operator bool() const { return plan_ != nullptr; }

private:
  Plan plan_ = nullptr;
};

/** \brief Owns an fftw_plan (double precision). */
using FftwPlan = BasicFftwPlan<double>;

} // namespace detail
} // namespace pcl::phaser
