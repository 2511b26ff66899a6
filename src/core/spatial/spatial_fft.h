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

/** \brief Forward r2c 3-D DFT of the nx x ny x nz row-major array \a in into the
 *  nx x ny x (nz/2+1) array \a out (FFTW's layout and sign, unnormalized).
 *
 * Computed as one 2-D r2c per x slab, then 1-D complex transforms along x, one batch
 * per y row. The pieces are fixed by the dims alone and each is one FFTW plan
 * execution, so the threads only decide who runs a piece: the result is bit-identical
 * for any thread count (FFTW's own threaded plans split by thread count). An all-zero
 * slab is not transformed (its transform is zero). Plans are cached per dims;
 * thread-safe. \a in is not modified; both arrays must come from fftw_malloc. */
void forwardFft3d(const Eigen::Vector3i& dims, const double* in,
                  std::complex<double>* out, int num_threads);

/** \brief Inverse c2r 3-D DFT (unnormalized), the exact reverse split of forwardFft3d.
 *  \a in (nx x ny x (nz/2+1)) is destroyed; \a out receives nx x ny x nz reals.
 *  \param[in] prepare if set, called once for every contiguous run [first, first +
 *  count) of \a in (the nz/2+1 coefficients of one (x, y)) just before its transform,
 *  from whichever thread transforms it; it may rewrite that run only. It lets an
 *  element-wise product run inside the transform's loop instead of its own. */
void inverseFft3d(
    const Eigen::Vector3i& dims, std::complex<double>* in, double* out, int num_threads,
    const std::function<void(std::size_t first, std::size_t count)>& prepare = {});

} // namespace detail
} // namespace pcl::phaser
