/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "spatial/spatial_fft.h"
#include "support/fftw_support.h"
#include "support/instance_cache.h"
#include "support/parallel.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace pcl::phaser {
namespace detail {

namespace {

using RunPreparation = std::function<void(std::size_t first, std::size_t count)>;

/** The plans of one dims. A new-array execution needs the plan's alignment, and x slabs
 *  of an odd ny * nz alternate between two: a slab plan per alignment. */
struct Fft3dPlans {
  std::size_t slab_real = 0;    ///< ny * nz
  std::size_t slab_complex = 0; ///< ny * (nz/2+1)
  int slab_alignment[2] = {0, 0};
  FftwPlan slab_forward[2]; ///< 2-D r2c, ny x nz -> ny x (nz/2+1)
  FftwPlan slab_inverse[2]; ///< 2-D c2r, destroys its input
  /** Rows of one y are gathered into a compact buffer first when the slab stride is a
   *  multiple of 1 KiB, where the strided plan thrashes the cache (measured 3x). */
  bool compact_rows = false;
  /** nz/2+1 in-place 1-D transforms along x (stride of a slab, or of a compact row). */
  FftwPlan row_forward;
  FftwPlan row_backward;

  int slabIndex(const double* p) const
  {
    return fftw_alignment_of(const_cast<double*>(p)) == slab_alignment[0] ? 0 : 1;
  }
};

std::shared_ptr<const Fft3dPlans> plansFor(const Eigen::Vector3i& dims)
{
  // Touch the planner mutex first: function-local statics die in reverse order of
  // construction, so the mutex outlives the cache whose plans lock it when destroyed.
  static std::mutex& planner_mutex = fftwPlannerMutex();
  static InstanceCache<std::array<int, 3>, Fft3dPlans> cache;
  return cache.get({dims.x(), dims.y(), dims.z()}, [&] {
    const int nx = dims.x(), ny = dims.y(), nz = dims.z(), nzh = nz / 2 + 1;
    auto plans = std::make_shared<Fft3dPlans>();
    plans->slab_real = static_cast<std::size_t>(ny) * nz;
    plans->slab_complex = static_cast<std::size_t>(ny) * nzh;
    const std::size_t rows = static_cast<std::size_t>(nx) * plans->slab_complex;
    // FFTW_ESTIMATE neither reads nor writes the arrays while planning.
    auto real = fftwAllocate<double>(plans->slab_real + 1);
    auto spectrum = fftwAllocate<fftw_complex>(rows);
    std::lock_guard<std::mutex> lock(planner_mutex);
    for (int k = 0; k < 2; ++k) {
      double* r = real.get() + k; // the second alignment of odd-sized slabs
      plans->slab_alignment[k] = fftw_alignment_of(r);
      plans->slab_forward[k] =
          FftwPlan(fftw_plan_dft_r2c_2d(ny, nz, r, spectrum.get(), kFftwFlags));
      plans->slab_inverse[k] =
          FftwPlan(fftw_plan_dft_c2r_2d(ny, nz, spectrum.get(), r, kFftwFlags));
    }
    plans->compact_rows = plans->slab_complex % 64 == 0;
    const int stride =
        plans->compact_rows ? nzh : static_cast<int>(plans->slab_complex);
    plans->row_forward = FftwPlan(fftw_plan_many_dft(
        1, &nx, nzh, spectrum.get(), nullptr, stride, 1, spectrum.get(), nullptr,
        stride, 1, FFTW_FORWARD, kFftwFlags));
    plans->row_backward = FftwPlan(fftw_plan_many_dft(
        1, &nx, nzh, spectrum.get(), nullptr, stride, 1, spectrum.get(), nullptr,
        stride, 1, FFTW_BACKWARD, kFftwFlags));
    for (int k = 0; k < 2; ++k)
      if (!plans->slab_forward[k] || !plans->slab_inverse[k])
        throw std::runtime_error(
            "pcl_phaser: FFTW could not plan the 2-D slab transforms");
    if (!plans->row_forward || !plans->row_backward)
      throw std::runtime_error(
          "pcl_phaser: FFTW could not plan the 1-D row transforms");
    return std::shared_ptr<const Fft3dPlans>(std::move(plans));
  });
}

fftw_complex* asFftw(std::complex<double>* p)
{
  return reinterpret_cast<fftw_complex*>(p);
}

/** Complex values between two threads' row buffers: \a size rounded up to 128 bytes,
 *  so each buffer keeps the alignment its plan was made for. */
std::size_t bufferStride(std::size_t size)
{
  return (size + 7) / 8 * 8;
}

/** One compact row buffer of \a size per thread slot when the plans gather rows. */
FftwBuffer<fftw_complex> rowBuffers(const Fft3dPlans& plans, std::size_t size,
                                    int num_threads)
{
  return plans.compact_rows
             ? fftwAllocate<fftw_complex>(bufferStride(size) *
                                          static_cast<std::size_t>(num_threads))
             : FftwBuffer<fftw_complex>();
}

/** Thread \a slot's buffer in \a buffers, or null. */
std::complex<double>* rowBuffer(const FftwBuffer<fftw_complex>& buffers,
                                std::size_t size, int slot)
{
  return buffers ? reinterpret_cast<std::complex<double>*>(buffers.get()) +
                       bufferStride(size) * static_cast<std::size_t>(slot)
                 : nullptr;
}

/** The 1-D transforms along x of row y (\a row coefficients at every x) of \a data:
 *  in place, or gathered into \a buffer and scattered back; \a prepare, if set, runs
 *  on each run of the row first. */
void transformRow(const Fft3dPlans& plans, fftw_plan plan, int nx, std::size_t row,
                  int y, std::complex<double>* data, std::complex<double>* buffer,
                  const RunPreparation& prepare = {})
{
  std::complex<double>* first = data + y * row;
  if (!plans.compact_rows) {
    if (prepare)
      for (int x = 0; x < nx; ++x)
        prepare(x * plans.slab_complex + y * row, row);
    fftw_execute_dft(plan, asFftw(first), asFftw(first));
    return;
  }
  for (int x = 0; x < nx; ++x) {
    if (prepare)
      prepare(x * plans.slab_complex + y * row, row);
    std::copy_n(first + x * plans.slab_complex, row, buffer + x * row);
  }
  fftw_execute_dft(plan, asFftw(buffer), asFftw(buffer));
  for (int x = 0; x < nx; ++x)
    std::copy_n(buffer + x * row, row, first + x * plans.slab_complex);
}

} // namespace

void forwardFft3d(const Eigen::Vector3i& dims, const double* in,
                  std::complex<double>* out, int num_threads)
{
  const auto plans = plansFor(dims);
  const int nx = dims.x(), ny = dims.y();
  const std::size_t row = plans->slab_complex / ny;
  const auto buffers = rowBuffers(*plans, nx * row, num_threads);
  parallelFor(nx, 4, num_threads, [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
    for (std::ptrdiff_t x = first; x < last; ++x) {
      // Out-of-place 2-D r2c preserves its input, so casting away const is safe.
      double* slab = const_cast<double*>(in) + x * plans->slab_real;
      std::complex<double>* transformed = out + x * plans->slab_complex;
      // The padding leaves many slabs of a source zero, and so is their transform.
      if (std::all_of(slab, slab + plans->slab_real, [](double v) { return v == 0.0; }))
        std::fill_n(transformed, plans->slab_complex, std::complex<double>(0.0));
      else
        fftw_execute_dft_r2c(plans->slab_forward[plans->slabIndex(slab)].get(), slab,
                             asFftw(transformed));
    }
  });
  parallelFor(ny, 4, num_threads,
              [&](std::ptrdiff_t first, std::ptrdiff_t last, int slot) {
                std::complex<double>* buffer = rowBuffer(buffers, nx * row, slot);
                for (std::ptrdiff_t y = first; y < last; ++y)
                  transformRow(*plans, plans->row_forward.get(), nx, row,
                               static_cast<int>(y), out, buffer);
              });
}

void inverseFft3d(
    const Eigen::Vector3i& dims, std::complex<double>* in, double* out, int num_threads,
    const std::function<void(std::size_t first, std::size_t count)>& prepare)
{
  const auto plans = plansFor(dims);
  const int nx = dims.x(), ny = dims.y();
  const std::size_t row = plans->slab_complex / ny;
  const auto buffers = rowBuffers(*plans, nx * row, num_threads);
  parallelFor(ny, 4, num_threads,
              [&](std::ptrdiff_t first, std::ptrdiff_t last, int slot) {
                std::complex<double>* buffer = rowBuffer(buffers, nx * row, slot);
                for (std::ptrdiff_t y = first; y < last; ++y)
                  transformRow(*plans, plans->row_backward.get(), nx, row,
                               static_cast<int>(y), in, buffer, prepare);
              });
  parallelFor(nx, 4, num_threads, [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
    for (std::ptrdiff_t x = first; x < last; ++x) {
      double* slab = out + x * plans->slab_real;
      fftw_execute_dft_c2r(plans->slab_inverse[plans->slabIndex(slab)].get(),
                           asFftw(in + x * plans->slab_complex), slab);
    }
  });
}

} // namespace detail
} // namespace pcl::phaser
