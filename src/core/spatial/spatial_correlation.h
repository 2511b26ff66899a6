/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <Eigen/Core>

#include <complex>
#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

namespace pcl::phaser {

namespace detail {

/** \brief FFTW-aligned buffers (bufferAcquire, bufferRelease: reused within an align),
 *  without <fftw3.h> here; \throws std::bad_alloc. */
void* spatialBufferAllocate(std::size_t bytes);
void spatialBufferFree(void* p, std::size_t bytes) noexcept;

/** \brief Allocator of FFTW-aligned memory: FFTW's new-array execute functions need the
 *  SIMD alignment the plan was made with, which std::allocator does not promise.
 *  Elements added without a value are left uninitialized, not zeroed: the FFTs that
 *  fill volumes and spectra write them whole. */
template <typename T>
struct SpatialAllocator {
  using value_type = T;
  SpatialAllocator() = default;
  template <typename U>
  SpatialAllocator(const SpatialAllocator<U>&) noexcept
  {
  }
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>)
  {
    // std::complex's default constructor zeroes; its bytes are written before use.
    if constexpr (!std::is_same_v<U, std::complex<double>> &&
                  !std::is_same_v<U, std::complex<float>>)
      ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  T* allocate(std::size_t n)
  {
    return static_cast<T*>(spatialBufferAllocate(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { spatialBufferFree(p, n * sizeof(T)); }
  template <typename U>
  bool operator==(const SpatialAllocator<U>&) const noexcept
  {
    return true;
  }
  template <typename U>
  bool operator!=(const SpatialAllocator<U>&) const noexcept
  {
    return false;
  }
};

} // namespace detail

/** \brief Real array of voxel values, FFTW-aligned. */
using SpatialRealArray = std::vector<double, detail::SpatialAllocator<double>>;
/** \brief Complex array of spectral coefficients, FFTW-aligned. */
using SpatialComplexArray =
    std::vector<std::complex<double>, detail::SpatialAllocator<std::complex<double>>>;

/** \brief Axis-aligned voxel grid with cubic voxels: voxel i covers [origin + i *
 *  voxel_size, origin + (i + 1) * voxel_size) on each axis. Memory is row-major with z
 *  fastest, flat = (ix * ny + iy) * nz + iz (FFTW's layout). */
struct SpatialGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(); ///< corner of voxel 0, meters
  double voxel_size = 1.0;                          ///< voxel edge, meters
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();   ///< voxels along x, y, z

  /** \brief Number of voxels nx * ny * nz. */
  std::size_t size() const
  {
    return static_cast<std::size_t>(dims.x()) * static_cast<std::size_t>(dims.y()) *
           static_cast<std::size_t>(dims.z());
  }

  /** \brief Flat index of voxel (ix, iy, iz); no range check. */
  std::size_t flatIndex(int ix, int iy, int iz) const
  {
    return (static_cast<std::size_t>(ix) * static_cast<std::size_t>(dims.y()) +
            static_cast<std::size_t>(iy)) *
               static_cast<std::size_t>(dims.z()) +
           static_cast<std::size_t>(iz);
  }

  /** \brief Inverse of flatIndex. */
  Eigen::Vector3i voxelIndex(std::size_t flat) const
  {
    const std::size_t nz = static_cast<std::size_t>(dims.z());
    const std::size_t ny = static_cast<std::size_t>(dims.y());
    return {static_cast<int>(flat / (ny * nz)), static_cast<int>((flat / nz) % ny),
            static_cast<int>(flat % nz)};
  }

  /** \brief Edge lengths of the grid in meters. */
  Eigen::Vector3d extent() const { return dims.cast<double>() * voxel_size; }
};

/** \brief How makeSpatialGrid sizes a grid around the target points. */
struct SpatialGridParameters {
  /** \brief Voxels along the longest axis (8..1024, rounded up to 2^a 3^b 5^c), used
   *  when voxel_size is 0. */
  int grid_size = 128;
  /** \brief Voxel size in meters; > 0 overrides grid_size (dims must stay <= 1024). */
  double voxel_size = 0.0;
  /** \brief Margin on each side of every axis, as a fraction of its extent: 0.5 makes
   *  the circular correlation of equal supports the linear one. */
  double padding = 0.5;
  /** \brief Lower bound of the per-side margin in meters (e.g. z of a ground robot). */
  double min_margin = 0.0;
};

/** \brief Smallest m >= n (and m >= 1) of the form 2^a 3^b 5^c. */
int nextFftFriendlySize(int n);

/** \brief A grid centered on the finite \a points: per axis of extent e it covers e +
 *  2 max(padding e, min_margin) plus one splat voxel per side, rounded up to an
 *  FFT-friendly count >= 8.
 *  \throws InvalidArgument for illegal parameters, no finite points, coinciding points
 *  (with grid_size), or more than 1024 voxels on an axis. */
SpatialGrid makeSpatialGrid(const Eigen::Matrix3Xd& points,
                            const SpatialGridParameters& parameters = {});

/** \brief Real values on a SpatialGrid (voxel values or a correlation surface). */
struct SpatialVolume {
  SpatialGrid grid;
  SpatialRealArray values; ///< grid.size() values in flatIndex order
};

/** \brief How voxelize turns splatted points into voxel values. */
struct SpatialVoxelParameters {
  /** \brief Saturation W0 of the soft occupancy W0 (1 - exp(-W / W0)), in points;
   *  0: linear density W. */
  double saturation = 1.0;
  /** \brief Worker threads (0 = OpenMP default); the result does not depend on it. */
  int num_threads = 1;
};

/** \brief Trilinear splat of \a points into \a grid: each point spreads its
 *  interpolation weights over the 8 voxel centers around it (weights outside the grid
 *  are dropped), and a voxel of summed weight W stores W0 (1 - exp(-W / W0)): the
 *  saturation keeps the dense voxels near the sensor from pulling the shift towards
 *  stacking the two sensors. Non-finite points are skipped; bit-identical for any
 *  thread count.
 *  \throws InvalidArgument if the grid is invalid, saturation < 0 or num_threads < 0.
 */
SpatialVolume voxelize(const SpatialGrid& grid, const Eigen::Matrix3Xd& points,
                       const SpatialVoxelParameters& parameters = {});

/** \brief Half-spectrum of a real 3-D grid, unnormalized, in FFTW's r2c layout:
 *  nx * ny * hz coefficients, flat (ix * ny + iy) * hz + kz, hz = nz / 2 + 1. */
struct SpatialSpectrum {
  SpatialGrid grid; ///< of the transformed volume
  SpatialComplexArray coefficients;

  /** \brief Number of stored kz values, nz / 2 + 1. */
  int halfZ() const { return grid.dims.z() / 2 + 1; }

  /** \brief Full-spectrum coefficients the stored one stands for: 1 on the planes kz =
   *  0 and kz = nz/2 (even nz), else 2. */
  int multiplicity(std::size_t flat) const
  {
    const int kz = static_cast<int>(flat % static_cast<std::size_t>(halfZ()));
    return (kz == 0 || 2 * kz == grid.dims.z()) ? 1 : 2;
  }
};

/** \brief r2c 3-D FFT of \a volume, bit-identical for any \a num_threads (0 = OpenMP
 *  default). \throws InvalidArgument for an invalid volume or num_threads < 0. */
SpatialSpectrum computeSpectrum(const SpatialVolume& volume, int num_threads = 1);

/** \brief Circular cross-correlation c[tau] = sum_x f[x + tau] g[x] of \a target f and
 *  \a source g, as c2r(F conj(G)) / N. Its origin is the shift of lag 0,
 *  target.grid.origin - source.grid.origin; lag index i stands for i, or i - n past
 *  n / 2. A target equal to the source moved by +t peaks at lag t.
 *  \throws InvalidArgument if dims or voxel sizes differ or num_threads < 0. */
SpatialVolume correlateSpectra(const SpatialSpectrum& target,
                               const SpatialSpectrum& source, int num_threads = 1);

/** \brief The correlation with each coefficient of F conj(G) divided by its magnitude
 *  to the power \a exponent (0: plain, 1: phase correlation), consuming \a source.
 *  Whitening flattens the broad overlap hill of two occupancy grids (which favors
 *  stacking the two sensors) and keeps the sharp peak of the structures they share.
 *  \throws InvalidArgument as correlateSpectra, or if exponent is outside [0, 1]. */
SpatialVolume correlateSpectraWhitened(const SpatialSpectrum& target,
                                       SpatialSpectrum&& source, double exponent,
                                       int num_threads = 1);

/** \brief Sub-voxel peak interpolation, per axis through the peak and its 2 wrapped
 *  neighbors. Worst axis error measured on random 40 x 30 x 8 m clouds: none 0.5 voxel,
 *  parabola 0.10, Gaussian 0.05-0.095. */
enum class SpatialPeakRefinement {
  kNone,      ///< integer argmax only (error up to 0.5 voxel)
  kParabolic, ///< parabola through the raw values
  kGaussian,  ///< parabola through the logs (kParabolic if a value is <= 1e-6 peak)
};

/** \brief A peak of the translation search. */
struct SpatialCorrelationResult {
  Eigen::Vector3d shift = Eigen::Vector3d::Zero(); ///< meters, moves source onto target
  Eigen::Vector3d lag = Eigen::Vector3d::Zero(); ///< voxels: shift = origin + lag voxel
  Eigen::Vector3i index = Eigen::Vector3i::Zero(); ///< integer argmax, each in [0, n)
  double peak_value = 0.0;                         ///< correlation at index
  /** \brief Peak-to-sidelobe ratio of the discrete Laplacian L (c minus the mean of its
   *  6 face neighbors): (L(peak) - mean L) / stddev L over the lags outside the 5x5x5
   *  block of the peak; 0 for a flat surface. */
  double score = 0.0;
};

/** \brief The refined maximum of a correlation volume (ties: lowest flat index; an
 *  all-zero volume gives index 0, value 0); the score only \a with_score.
 *  Deterministic for any \a num_threads.
 *  \throws InvalidArgument if the volume is invalid or num_threads < 0. */
SpatialCorrelationResult
findSpatialPeak(const SpatialVolume& correlation,
                SpatialPeakRefinement refinement = SpatialPeakRefinement::kGaussian,
                int num_threads = 1, bool with_score = true);

/** \brief Up to \a count highest local maxima (>= their 6 wrapped face neighbors),
 *  highest first, each more than \a separation voxels away on some axis from every
 *  higher one taken; refined as findSpatialPeak, without a score.
 *  \throws InvalidArgument if the volume is invalid or an argument negative. */
std::vector<SpatialCorrelationResult> findDistinctSpatialPeaks(
    const SpatialVolume& correlation, int count, int separation,
    SpatialPeakRefinement refinement = SpatialPeakRefinement::kGaussian);

} // namespace pcl::phaser
