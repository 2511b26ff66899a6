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

// ---------------------------------------------------------------------------------------
// Aligned storage. FFTW's new-array execute functions need arrays with the same SIMD
// alignment as the arrays the plan was made with; std::allocator does not promise that
// (glibc returns 16-byte aligned blocks for large sizes), so volumes and spectra use an
// allocator backed by fftw_malloc. The header stays free of <fftw3.h>.
namespace detail {

/** \brief fftw_malloc wrapper; \throws std::bad_alloc. Defined in
 *  spatial_correlation.cpp. */
void* spatialBufferAllocate(std::size_t bytes);

/** \brief fftw_free wrapper. */
void spatialBufferFree(void* p) noexcept;

/** \brief std::allocator replacement that returns FFTW-aligned memory. Elements added
 *  without a value are default-initialized (left as they are for double), not zeroed:
 *  the volumes and spectra are written whole by the FFTs that fill them, and zeroing
 *  megabytes first cost a single-threaded pass over each. */
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
  void deallocate(T* p, std::size_t) noexcept { spatialBufferFree(p); }
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

// ---------------------------------------------------------------------------------------
/** \brief Axis-aligned voxel grid: isotropic voxel size, origin at the outer corner of
 *  voxel (0, 0, 0), per-axis dimensions that need not be equal.
 *
 *  Voxel (ix, iy, iz) covers [origin + i * voxel_size, origin + (i + 1) * voxel_size)
 *  on each axis; its center is origin + (i + 0.5) * voxel_size. Memory is row-major
 *  with z fastest: flat = (ix * ny + iy) * nz + iz (the layout FFTW's 3-D transforms
 *  expect). */
struct SpatialGrid {
  /** \brief Corner of voxel (0, 0, 0) in meters. */
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  /** \brief Edge length of a voxel in meters. */
  double voxel_size = 1.0;
  /** \brief Number of voxels along x, y, z. */
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();

  /** \brief Total number of voxels nx * ny * nz. */
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

  /** \brief Edge lengths of the whole grid in meters. */
  Eigen::Vector3d extent() const { return dims.cast<double>() * voxel_size; }

  /** \brief Center of voxel \a index in meters. */
  Eigen::Vector3d voxelCenter(const Eigen::Vector3i& index) const
  {
    return origin + (index.cast<double>().array() + 0.5).matrix() * voxel_size;
  }

  /** \brief True if \a p lies inside the grid's box. */
  bool contains(const Eigen::Vector3d& p) const
  {
    const Eigen::Array3d u = (p - origin).array() / voxel_size;
    return (u >= 0.0).all() && (u < dims.cast<double>().array()).all();
  }
};

/** \brief How makeSpatialGrid sizes a grid around the target points. */
struct SpatialGridParameters {
  /** \brief Voxels along the longest axis (legal 8..1024, rounded up to 2^a 3^b 5^c).
   *  Used when voxel_size == 0; the voxel size then follows from the padded extent. */
  int grid_size = 128;
  /** \brief Explicit voxel size in meters; > 0 overrides grid_size, 0 means unset,
   *  negative is illegal. The per-axis dims then follow from the padded extent and must
   *  stay <= 1024. */
  double voxel_size = 0.0;
  /** \brief Margin added on each side of every axis, as a fraction of that axis's
   *  extent. 0.5 doubles each axis, which makes the circular correlation of two equally
   *  sized supports equal to the linear one and allows shifts up to half the extent. */
  double padding = 0.5;
  /** \brief Lower bound of the per-side margin in meters (largest expected shift along
   *  a thin axis, e.g. z of a ground-robot scan). */
  double min_margin = 0.0;
};

/** \brief Smallest m >= n (and m >= 1) of the form 2^a 3^b 5^c. */
int nextFftFriendlySize(int n);

/** \brief Builds a grid that holds \a points (the target) with padding.
 *
 *  Per axis a with bounding-box extent e_a the covered length is e_a + 2 *
 *  max(padding*e_a, min_margin) plus one voxel per side for the trilinear splat,
 *  rounded up to an FFT-friendly voxel count (at least 8); the extra voxels from
 *  rounding are split evenly, so the box stays centered on the points. The grid depends
 *  on the target only, so its spectrum can be cached; a source voxelized into it loses
 *  the points that fall outside (they are dropped, never wrapped). Non-finite points
 *  are ignored.
 *  \throws InvalidArgument for illegal parameters, for a point set without finite
 *  points, when grid_size is used but all points coincide, or when explicit voxel_size
 *  needs more than 1024 voxels on an axis. */
SpatialGrid makeSpatialGrid(const Eigen::Matrix3Xd& points,
                            const SpatialGridParameters& parameters = {});

// ---------------------------------------------------------------------------------------
/** \brief Real values on a SpatialGrid (voxel values or a correlation surface). */
struct SpatialVolume {
  /** \brief Geometry of the values. */
  SpatialGrid grid;
  /** \brief grid.size() values in grid.flatIndex order. */
  SpatialRealArray values;
};

/** \brief How voxelize turns splatted points into voxel values. */
struct SpatialVoxelParameters {
  /** \brief Saturation weight W0 (> 0) of the soft occupancy W0 * (1 - exp(-W / W0)),
   *  in points; 0 disables saturation (linear density W). */
  double saturation = 1.0;
  /** \brief OpenMP threads (0 = OpenMP default); the result does not depend on it. */
  int num_threads = 1;
};

/** \brief Voxelizes \a points into \a grid with trilinear splatting, each point with
 *  value 1.
 *
 *  Every point spreads the weights of linear interpolation to the 8 voxel centers
 *  around it (so the correlation surface is smooth in the shift and its peak can be
 *  interpolated); weights that land outside the grid are dropped, never wrapped. With W
 *  the summed weight and S the summed weight * value of a voxel, the stored value is
 *  (S/W) * W0*(1 - exp(-W/W0)): the weighted mean value times a soft occupancy.
 *  Saturating keeps near-sensor voxels, which hold far more lidar returns than distant
 *  ones, from dominating the correlation (that would pull the shift towards aligning
 *  the two sensor positions), while a single point stays almost linear in its weights;
 *  the mean makes a channel (intensity, ...) independent of point density, as in the
 *  original. With value 1 this is W0*(1 - exp(-W/W0)). Linear density (saturation 0)
 *  interpolates the peak of uniformly dense surfaces better but has no density guard.
 *  Non-finite points and values are skipped. The result is bit-identical for any thread
 *  count: each voxel is summed by one thread in a fixed point order.
 *  \throws InvalidArgument if the grid is invalid, saturation < 0 or num_threads < 0.
 */
SpatialVolume voxelize(const SpatialGrid& grid, const Eigen::Matrix3Xd& points,
                       const SpatialVoxelParameters& parameters = {});

/** \brief As above with one value per point (e.g. a normalized channel).
 *  \throws InvalidArgument also if values.size() != points.cols(). */
SpatialVolume voxelize(const SpatialGrid& grid, const Eigen::Matrix3Xd& points,
                       const Eigen::VectorXd& values,
                       const SpatialVoxelParameters& parameters = {});

// ---------------------------------------------------------------------------------------
/** \brief Half-spectrum of a real 3-D grid (FFTW r2c layout), cacheable per target.
 *
 *  coefficients holds nx * ny * (nz / 2 + 1) values, flat index (ix * ny + iy) * hz +
 *  kz with hz = nz / 2 + 1. The omitted kz < 0 half is the complex conjugate of the
 *  stored one (Hermitian symmetry). Unnormalized: coefficient(0) is the sum of all
 *  voxel values. */
struct SpatialSpectrum {
  /** \brief Geometry of the transformed volume (gives the frequencies). */
  SpatialGrid grid;
  /** \brief The stored half-spectrum. */
  SpatialComplexArray coefficients;

  /** \brief Number of stored kz values, nz / 2 + 1. */
  int halfZ() const { return grid.dims.z() / 2 + 1; }

  /** \brief Signed integer frequency (kx, ky, kz) of stored coefficient \a flat: kx in
   *  (-nx/2, nx/2], ky likewise, kz in [0, nz/2]. */
  Eigen::Vector3i frequencyIndex(std::size_t flat) const
  {
    const std::size_t hz = static_cast<std::size_t>(halfZ());
    const std::size_t ny = static_cast<std::size_t>(grid.dims.y());
    int kx = static_cast<int>(flat / (ny * hz));
    int ky = static_cast<int>((flat / hz) % ny);
    const int kz = static_cast<int>(flat % hz);
    if (kx > grid.dims.x() / 2)
      kx -= grid.dims.x();
    if (ky > grid.dims.y() / 2)
      ky -= grid.dims.y();
    return {kx, ky, kz};
  }

  /** \brief Frequency of coefficient \a flat in cycles per meter, k_a / (n_a * voxel).
   *  Its norm is the radial frequency a band-pass fusion should use: unlike the integer
   *  index it is comparable across axes of different length. */
  Eigen::Vector3d frequency(std::size_t flat) const
  {
    return frequencyIndex(flat).cast<double>().cwiseQuotient(grid.extent());
  }

  /** \brief How many full-spectrum coefficients the stored one stands for: 1 on the kz
   *  = 0 and kz = nz/2 (even nz) planes, whose partners are stored too, else 2. */
  int multiplicity(std::size_t flat) const
  {
    const int kz = static_cast<int>(flat % static_cast<std::size_t>(halfZ()));
    return (kz == 0 || 2 * kz == grid.dims.z()) ? 1 : 2;
  }
};

/** \brief r2c 3-D FFT of \a volume (plans cached per dims; thread-safe).
 *  \param[in] volume the voxel values
 *  \param[in] num_threads worker threads (0 = OpenMP default); the result is
 *  bit-identical for any count
 *  \throws InvalidArgument if values.size() != grid.size(), the grid is invalid or
 *  num_threads < 0. */
SpatialSpectrum computeSpectrum(const SpatialVolume& volume, int num_threads = 1);

/** \brief Circular cross-correlation c[tau] = sum_x f[x + tau] g[x] of the \a target f
 *  and the \a source g, computed as c2r(F * conj(G)) / N, so the values equal the sum
 *  exactly.
 *
 *  The returned volume has the spectra's dims and voxel size; its origin is the metric
 *  shift of lag 0, target.grid.origin - source.grid.origin (zero when both were
 *  voxelized into one grid). Lag index i stands for i, or i - n when i > n / 2. If the
 *  target equals the source moved by +t, the peak is at lag t.
 *  \throws InvalidArgument if dims or voxel sizes differ or num_threads < 0. */
SpatialVolume correlateSpectra(const SpatialSpectrum& target,
                               const SpatialSpectrum& source, int num_threads = 1);

/** \brief The same, consuming \a source: its buffer holds the product, which saves
 *  allocating (and first touching) a spectrum-sized array per correlation. */
SpatialVolume correlateSpectra(const SpatialSpectrum& target, SpatialSpectrum&& source,
                               int num_threads = 1);

/** \brief The correlation with a partly whitened cross-power spectrum: each
 *  coefficient of F conj(G) divided by its magnitude to the power \a exponent (0: plain
 *  correlation, 1: phase correlation), consuming \a source. Whitening flattens the
 *  broad overlap hill of two finite occupancy grids (which favors the shift that
 *  stacks their centers, i.e. the two sensors) and keeps the sharp peak of the
 *  structures they share.
 *  \throws InvalidArgument as correlateSpectra, or if exponent is outside [0, 1]. */
SpatialVolume correlateSpectraWhitened(const SpatialSpectrum& target,
                                       SpatialSpectrum&& source, double exponent,
                                       int num_threads = 1);

/** \brief Sub-voxel peak interpolation, per axis through the peak and its 2 neighbors
 *  (wrapping around). Measured on random 40 x 30 x 8 m clouds (worst axis error over
 *  the test shifts): none 0.5 voxel, parabola 0.10, Gaussian 0.05-0.095; a 3x3x3
 *  least-squares quadric was also tried and was not better than the Gaussian. The
 *  residual is a bias from the peak shape that vanishes at zero offset: moving the
 *  source by the estimate, re-voxelizing and correlating again leaves ~0.002-0.01. */
enum class SpatialPeakRefinement {
  kNone,      ///< integer argmax only (error up to 0.5 voxel)
  kParabolic, ///< parabola through the raw values
  kGaussian,  ///< parabola through the logs (kParabolic if a value is <= 1e-6 peak)
};

/** \brief Result of the translation search. */
struct SpatialCorrelationResult {
  /** \brief Translation in meters that moves the source onto the target (sub-voxel). */
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
  /** \brief Signed lag in voxels, sub-voxel refined (shift = origin + lag * voxel). */
  Eigen::Vector3d lag = Eigen::Vector3d::Zero();
  /** \brief Integer argmax in the correlation volume, each in [0, n). */
  Eigen::Vector3i index = Eigen::Vector3i::Zero();
  /** \brief Correlation value at index. */
  double peak_value = 0.0;
  /** \brief Peak quality: peak-to-sidelobe ratio of the correlation's discrete
   *  Laplacian (c minus the mean of its 6 face neighbors), (L(peak) - mean L) / stddev
   *  L over the lags outside the 5x5x5 neighborhood of the peak. The high-pass ignores
   *  the broad overlap pyramid of occupancy correlations, so a true match scores far
   *  above unrelated clouds. 0 for a flat (e.g. all-zero) surface. */
  double score = 0.0;
};

/** \brief Finds and refines the maximum of a correlation volume from correlateSpectra.
 *  Ties go to the lowest flat index; neighbors wrap around. Without \a with_score the
 *  peak-to-sidelobe score (a pass over the whole volume) is left at 0. Deterministic
 * for any \a num_threads. An all-zero volume (empty source or target) gives lag index
 * 0, peak value 0 and score 0. \throws InvalidArgument if the volume is invalid or
 * num_threads < 0. */
SpatialCorrelationResult
findSpatialPeak(const SpatialVolume& correlation,
                SpatialPeakRefinement refinement = SpatialPeakRefinement::kGaussian,
                int num_threads = 1, bool with_score = true);

/** \brief The \a count (>= 0) highest distinct peaks of a correlation volume, highest
 *  first: local maxima (at least as high as their six face neighbors, wrapped), each
 *  more than \a separation (>= 0) voxels away on some axis from every higher one taken;
 *  fewer when the volume has fewer. Refined as findSpatialPeak, without a score; single
 *  threaded. \throws InvalidArgument if the volume is invalid or an argument negative.
 */
std::vector<SpatialCorrelationResult> findDistinctSpatialPeaks(
    const SpatialVolume& correlation, int count, int separation,
    SpatialPeakRefinement refinement = SpatialPeakRefinement::kGaussian);

/** \brief correlateSpectra followed by findSpatialPeak. */
SpatialCorrelationResult
correlateSpatial(const SpatialSpectrum& target, const SpatialSpectrum& source,
                 SpatialPeakRefinement refinement = SpatialPeakRefinement::kGaussian,
                 int num_threads = 1);

} // namespace pcl::phaser
