/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "fftw_support.h"
#include "instance_cache.h"
#include "spatial_fft.h"

#include <array>
#include <cstddef>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace pcl::phaser {
namespace detail {

namespace {

/** The plans of one dims. A new-array execution needs the alignment the plan was made
 *  for; x slabs of an odd ny * nz alternate between two, so slabs get a plan per
 * alignment. Rows of complex values are always aligned alike. */
struct Fft3dPlans {
  std::size_t slab_real = 0;    ///< ny * nz
  std::size_t slab_complex = 0; ///< ny * (nz/2+1)
  int slab_alignment[2] = {0, 0};
  FftwPlan slab_forward[2]; ///< 2-D r2c, ny x nz -> ny x (nz/2+1)
  FftwPlan slab_inverse[2]; ///< 2-D c2r, destroys its input
  FftwPlan row_forward; ///< nz/2+1 in-place 1-D transforms along x, stride ny*(nz/2+1)
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
    const int stride = static_cast<int>(plans->slab_complex);
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

} // namespace

void forwardFft3d(const Eigen::Vector3i& dims, const double* in,
                  std::complex<double>* out, int num_threads)
{
  const auto plans = plansFor(dims);
  const int nx = dims.x(), ny = dims.y();
  const std::size_t row = plans->slab_complex / ny;
  // One parallel region for both passes (the implicit barrier of the first loop
  // separates them): one team start per transform, not two.
#pragma omp parallel num_threads(num_threads)
  {
#pragma omp for schedule(dynamic, 4)
    for (int x = 0; x < nx; ++x) {
      // Out-of-place 2-D r2c preserves its input, so casting away const is safe.
      double* slab = const_cast<double*>(in) + x * plans->slab_real;
      fftw_execute_dft_r2c(plans->slab_forward[plans->slabIndex(slab)].get(), slab,
                           asFftw(out + x * plans->slab_complex));
    }
#pragma omp for schedule(dynamic, 4)
    for (int y = 0; y < ny; ++y)
      fftw_execute_dft(plans->row_forward.get(), asFftw(out + y * row),
                       asFftw(out + y * row));
  }
}

void inverseFft3d(
    const Eigen::Vector3i& dims, std::complex<double>* in, double* out, int num_threads,
    const std::function<void(std::size_t first, std::size_t count)>& prepare)
{
  const auto plans = plansFor(dims);
  const int nx = dims.x(), ny = dims.y();
  const std::size_t row = plans->slab_complex / ny;
#pragma omp parallel num_threads(num_threads)
  {
#pragma omp for schedule(dynamic, 4)
    for (int y = 0; y < ny; ++y) {
      // Row y's 1-D transforms read (x, y) for every x: prepare exactly those runs.
      if (prepare)
        for (int x = 0; x < nx; ++x)
          prepare(x * plans->slab_complex + y * row, row);
      fftw_execute_dft(plans->row_backward.get(), asFftw(in + y * row),
                       asFftw(in + y * row));
    }
#pragma omp for schedule(dynamic, 4)
    for (int x = 0; x < nx; ++x) {
      double* slab = out + x * plans->slab_real;
      fftw_execute_dft_c2r(plans->slab_inverse[plans->slabIndex(slab)].get(),
                           asFftw(in + x * plans->slab_complex), slab);
    }
  }
}

} // namespace detail
} // namespace pcl::phaser
