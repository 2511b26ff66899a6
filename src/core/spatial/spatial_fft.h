/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The 3-D real FFT of the spatial correlation, split so that both cores work on it.
 */
#pragma once

#include <Eigen/Core>

#include <complex>
#include <cstddef>
#include <functional>

namespace pcl::phaser {
namespace detail {

/** \brief Forward r2c 3-D DFT (unnormalized) of the nx x ny x nz array \a in into the
 *  nx x ny x (nz/2+1) array \a out, both from fftw_malloc: one 2-D r2c per x slab,
 *  then 1-D transforms along x per y row. The pieces depend on the dims alone, so the
 *  result is bit-identical for any thread count (FFTW's threaded plans are not). */
void forwardFft3d(const Eigen::Vector3i& dims, const double* in,
                  std::complex<double>* out, int num_threads);
/** \brief forwardFft3d in single precision (libfftw3f), for pass 1's correlations. */
void forwardFft3d(const Eigen::Vector3i& dims, const float* in,
                  std::complex<float>* out, int num_threads);

/** \brief Inverse c2r 3-D DFT (unnormalized), the reverse of forwardFft3d; destroys
 *  \a in. \param[in] prepare if set, called for every run [first, first + count) of
 *  \a in (the coefficients of one (x, y)) just before its transform; it may rewrite
 *  that run only. */
void inverseFft3d(
    const Eigen::Vector3i& dims, std::complex<double>* in, double* out, int num_threads,
    const std::function<void(std::size_t first, std::size_t count)>& prepare = {});
/** \brief inverseFft3d in single precision (libfftw3f). */
void inverseFft3d(
    const Eigen::Vector3i& dims, std::complex<float>* in, float* out, int num_threads,
    const std::function<void(std::size_t first, std::size_t count)>& prepare = {});

} // namespace detail
} // namespace pcl::phaser
