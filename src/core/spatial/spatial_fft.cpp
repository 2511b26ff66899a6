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

/** The plans of one dims in precision \a Real. A new-array execution needs the plan's
 *  alignment, and x slabs of an odd ny * nz cycle through 16 / sizeof(Real) of them
 * (two in double, up to four in float): a slab plan per alignment. */
template <typename Real>
struct Fft3dPlans {
  static constexpr int kAlignments = static_cast<int>(16 / sizeof(Real));
  using Plan = BasicFftwPlan<Real>;
  std::size_t slab_real = 0;    ///< ny * nz
  std::size_t slab_complex = 0; ///< ny * (nz/2+1)
  int slab_alignment[kAlignments] = {};
  Plan slab_forward[kAlignments]; ///< 2-D r2c, ny x nz -> ny x (nz/2+1)
  Plan slab_inverse[kAlignments]; ///< 2-D c2r, destroys its input
  /** Rows of one y are gathered into a compact buffer first when the slab stride is a
   *  multiple of 1 KiB, where the strided plan thrashes the cache (measured 3x). */
  bool compact_rows = false;
  /** nz/2+1 in-place 1-D transforms along x (stride of a slab, or of a compact row). */
  Plan row_forward;
  Plan row_backward;

  int slabIndex(const Real* p) const
  {
    const int alignment = Fftw<Real>::alignment_of(const_cast<Real*>(p));
    for (int k = 1; k < kAlignments; ++k)
      if (alignment == slab_alignment[k])
        return k;
    return 0;
  }
};

/** The plans of \a dims and \a Real, made under the planner mutex. */
template <typename Real>
std::shared_ptr<const Fft3dPlans<Real>> makePlans(const Eigen::Vector3i& dims,
                                                  std::mutex& planner_mutex)
{
  using Api = Fftw<Real>;
  using Plan = BasicFftwPlan<Real>;
  const int nx = dims.x(), ny = dims.y(), nz = dims.z(), nzh = nz / 2 + 1;
  auto plans = std::make_shared<Fft3dPlans<Real>>();
  plans->slab_real = static_cast<std::size_t>(ny) * nz;
  plans->slab_complex = static_cast<std::size_t>(ny) * nzh;
  const std::size_t rows = static_cast<std::size_t>(nx) * plans->slab_complex;
  // FFTW_ESTIMATE neither reads nor writes the arrays while planning.
  auto real = fftwAllocate<Real>(plans->slab_real + Fft3dPlans<Real>::kAlignments);
  auto spectrum = fftwAllocate<typename Api::Complex>(rows);
  std::lock_guard<std::mutex> lock(planner_mutex);
  for (int k = 0; k < Fft3dPlans<Real>::kAlignments; ++k) {
    Real* r = real.get() + k; // the other alignments of odd-sized slabs
    plans->slab_alignment[k] = Api::alignment_of(r);
    plans->slab_forward[k] =
        Plan(Api::plan_r2c_2d(ny, nz, r, spectrum.get(), kFftwFlags));
    plans->slab_inverse[k] =
        Plan(Api::plan_c2r_2d(ny, nz, spectrum.get(), r, kFftwFlags));
    if (!plans->slab_forward[k] || !plans->slab_inverse[k])
      throw std::runtime_error(
          "pcl_phaser: FFTW could not plan the 2-D slab transforms");
  }
  plans->compact_rows = plans->slab_complex * sizeof(std::complex<Real>) % 1024 == 0;
  const int stride = plans->compact_rows ? nzh : static_cast<int>(plans->slab_complex);
  for (int sign : {FFTW_FORWARD, FFTW_BACKWARD})
    (sign == FFTW_FORWARD ? plans->row_forward : plans->row_backward) =
        Plan(Api::plan_many_dft(1, &nx, nzh, spectrum.get(), nullptr, stride, 1,
                                spectrum.get(), nullptr, stride, 1, sign, kFftwFlags));
  if (!plans->row_forward || !plans->row_backward)
    throw std::runtime_error("pcl_phaser: FFTW could not plan the 1-D row transforms");
  return plans;
}

template <typename Real>
std::shared_ptr<const Fft3dPlans<Real>> plansFor(const Eigen::Vector3i& dims)
{
  // Touch the planner mutex first: function-local statics die in reverse order of
  // construction, so the mutex outlives the cache whose plans lock it when destroyed.
  static std::mutex& planner_mutex = fftwPlannerMutex();
  static InstanceCache<std::array<int, 3>, Fft3dPlans<Real>> cache;
  return cache.get({dims.x(), dims.y(), dims.z()},
                   [&] { return makePlans<Real>(dims, planner_mutex); });
}

template <typename Real>
typename Fftw<Real>::Complex* asFftw(std::complex<Real>* p)
{
  return reinterpret_cast<typename Fftw<Real>::Complex*>(p);
}

/** Complex values between two threads' row buffers: \a size rounded up to 128 bytes,
 *  so each buffer keeps the alignment its plan was made for. */
std::size_t bufferStride(std::size_t size)
{
  return (size + 7) / 8 * 8;
}

/** One compact row buffer of \a size per thread slot when the plans gather rows. */
template <typename Real>
FftwBuffer<std::complex<Real>> rowBuffers(const Fft3dPlans<Real>& plans,
                                          std::size_t size, int num_threads)
{
  return plans.compact_rows
             ? fftwAllocate<std::complex<Real>>(bufferStride(size) *
                                                static_cast<std::size_t>(num_threads))
             : FftwBuffer<std::complex<Real>>();
}

/** Thread \a slot's buffer in \a buffers, or null. */
template <typename Real>
std::complex<Real>* rowBuffer(const FftwBuffer<std::complex<Real>>& buffers,
                              std::size_t size, int slot)
{
  return buffers ? buffers.get() + bufferStride(size) * static_cast<std::size_t>(slot)
                 : nullptr;
}

/** The 1-D transforms along x of row y (\a row coefficients at every x) of \a data:
 *  in place, or gathered into \a buffer and scattered back; \a prepare, if set, runs
 *  on each run of the row first. */
template <typename Real>
void transformRow(const Fft3dPlans<Real>& plans, typename Fftw<Real>::Plan plan, int nx,
                  std::size_t row, int y, std::complex<Real>* data,
                  std::complex<Real>* buffer, const RunPreparation& prepare = {})
{
  std::complex<Real>* first = data + y * row;
  if (!plans.compact_rows) {
    if (prepare)
      for (int x = 0; x < nx; ++x)
        prepare(x * plans.slab_complex + y * row, row);
    Fftw<Real>::execute_dft(plan, asFftw(first), asFftw(first));
    return;
  }
  for (int x = 0; x < nx; ++x) {
    if (prepare)
      prepare(x * plans.slab_complex + y * row, row);
    std::copy_n(first + x * plans.slab_complex, row, buffer + x * row);
  }
  Fftw<Real>::execute_dft(plan, asFftw(buffer), asFftw(buffer));
  for (int x = 0; x < nx; ++x)
    std::copy_n(buffer + x * row, row, first + x * plans.slab_complex);
}

template <typename Real>
void forward(const Eigen::Vector3i& dims, const Real* in, std::complex<Real>* out,
             int num_threads)
{
  const auto plans = plansFor<Real>(dims);
  const int nx = dims.x(), ny = dims.y();
  const std::size_t row = plans->slab_complex / ny;
  const auto buffers = rowBuffers(*plans, nx * row, num_threads);
  parallelFor(nx, 4, num_threads, [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
    for (std::ptrdiff_t x = first; x < last; ++x) {
      // Out-of-place 2-D r2c preserves its input, so casting away const is safe.
      Real* slab = const_cast<Real*>(in) + x * plans->slab_real;
      std::complex<Real>* transformed = out + x * plans->slab_complex;
      // The padding leaves many slabs of a source zero, and so is their transform.
      if (std::all_of(slab, slab + plans->slab_real, [](Real v) { return v == 0; }))
        std::fill_n(transformed, plans->slab_complex, std::complex<Real>(0));
      else
        Fftw<Real>::execute_r2c(plans->slab_forward[plans->slabIndex(slab)].get(), slab,
                                asFftw(transformed));
    }
  });
  parallelFor(ny, 4, num_threads,
              [&](std::ptrdiff_t first, std::ptrdiff_t last, int slot) {
                std::complex<Real>* buffer = rowBuffer(buffers, nx * row, slot);
                for (std::ptrdiff_t y = first; y < last; ++y)
                  transformRow(*plans, plans->row_forward.get(), nx, row,
                               static_cast<int>(y), out, buffer);
              });
}

template <typename Real>
void inverse(const Eigen::Vector3i& dims, std::complex<Real>* in, Real* out,
             int num_threads, const RunPreparation& prepare)
{
  const auto plans = plansFor<Real>(dims);
  const int nx = dims.x(), ny = dims.y();
  const std::size_t row = plans->slab_complex / ny;
  const auto buffers = rowBuffers(*plans, nx * row, num_threads);
  parallelFor(ny, 4, num_threads,
              [&](std::ptrdiff_t first, std::ptrdiff_t last, int slot) {
                std::complex<Real>* buffer = rowBuffer(buffers, nx * row, slot);
                for (std::ptrdiff_t y = first; y < last; ++y)
                  transformRow(*plans, plans->row_backward.get(), nx, row,
                               static_cast<int>(y), in, buffer, prepare);
              });
  parallelFor(nx, 4, num_threads, [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
    for (std::ptrdiff_t x = first; x < last; ++x) {
      Real* slab = out + x * plans->slab_real;
      Fftw<Real>::execute_c2r(plans->slab_inverse[plans->slabIndex(slab)].get(),
                              asFftw(in + x * plans->slab_complex), slab);
    }
  });
}

} // namespace

void forwardFft3d(const Eigen::Vector3i& dims, const double* in,
                  std::complex<double>* out, int num_threads)
{
  forward(dims, in, out, num_threads);
}

void forwardFft3d(const Eigen::Vector3i& dims, const float* in,
                  std::complex<float>* out, int num_threads)
{
  forward(dims, in, out, num_threads);
}

void inverseFft3d(const Eigen::Vector3i& dims, std::complex<double>* in, double* out,
                  int num_threads, const RunPreparation& prepare)
{
  inverse(dims, in, out, num_threads, prepare);
}

void inverseFft3d(const Eigen::Vector3i& dims, std::complex<float>* in, float* out,
                  int num_threads, const RunPreparation& prepare)
{
  inverse(dims, in, out, num_threads, prepare);
}

} // namespace detail
} // namespace pcl::phaser
