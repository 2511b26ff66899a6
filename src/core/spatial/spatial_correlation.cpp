/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "spatial/spatial_correlation.h"
#include "spatial/spatial_fft.h"
#include "spatial/spatial_grid_support.h"
#include "spatial/spatial_single.h"
#include "support/buffer_pool.h"
#include "support/error.h"
#include "support/fftw_support.h"
#include "support/parallel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pcl::phaser {

namespace detail {

void* spatialBufferAllocate(std::size_t bytes)
{
  return bufferAcquire(bytes);
}

void spatialBufferFree(void* p, std::size_t bytes) noexcept
{
  bufferRelease(p, bytes);
}

} // namespace detail

namespace {

using detail::checkGrid;
using detail::checkVolume;
using detail::resolveThreads;

constexpr int kMinGridSize = 8;
constexpr int kMaxGridSize = 1024;

/** One point's trilinear footprint: lower corner voxel and the fractions towards the
 *  upper corner. */
struct Splat {
  Eigen::Vector3i base;
  Eigen::Vector3d frac;
};

/** Footprint of every point i in [first, last) into \a all, \a inside[i] = 1 when its
 *  continuous voxel coordinate u (voxel centers at integers) is finite and lies in
 *  [-1, n) on every axis (else 0); tested in double, before any integer conversion. */
void pointFootprints(const SpatialGrid& grid, const Eigen::Matrix3Xd& points,
                     Splat* all, char* inside, Eigen::Index first, Eigen::Index last)
{
  const Eigen::Array3d upper = grid.dims.cast<double>().array();
  for (Eigen::Index i = first; i < last; ++i) {
    const Eigen::Array3d u =
        (points.col(i) - grid.origin).array() / grid.voxel_size - 0.5;
    inside[i] = 0;
    if (!u.allFinite() || (u < -1.0).any() || (u >= upper).any())
      continue;
    const Eigen::Array3d lower = u.floor();
    all[i] = {lower.cast<int>().matrix(), (u - lower).matrix()};
    inside[i] = 1;
  }
}

/** Points per chunk of the counting sort, fixed so its order does not depend on the
 *  thread count. */
constexpr std::size_t kSortChunk = 16384;

/** Bucket of a footprint in the counting sort: its lower x index + 1, in [0, nx]. */
std::size_t bucketOf(const Splat& s)
{
  return static_cast<std::size_t>(s.base.x() + 1);
}

/** Stable counting sort of the footprints marked \a inside by lower x index into
 *  \a sorted, in parallel over chunks of kSortChunk points (counts per chunk, offsets
 * in bucket-then-chunk order, then a scatter), so each bucket holds its points in point
 *  order whatever the thread count. Bucket b (lower index b - 1) is [slab_start[b],
 *  slab_start[b + 1]). */
void sortBySlab(const Splat* all, const char* inside, std::size_t count, Splat* sorted,
                std::vector<std::size_t>& slab_start, int threads)
{
  const std::size_t buckets = slab_start.size() - 1;
  const std::size_t chunks = (count + kSortChunk - 1) / kSortChunk;
  std::vector<std::size_t> counts(chunks * buckets, 0);
  const auto eachChunk = [&](const auto& op) {
    detail::parallelFor(static_cast<std::ptrdiff_t>(chunks), 1, threads,
                        [&](std::ptrdiff_t c, std::ptrdiff_t, int) {
                          const std::size_t first =
                              static_cast<std::size_t>(c) * kSortChunk;
                          const std::size_t last = std::min(count, first + kSortChunk);
                          std::size_t* row =
                              counts.data() + static_cast<std::size_t>(c) * buckets;
                          for (std::size_t i = first; i < last; ++i)
                            if (inside[i])
                              op(i, row);
                        });
  };
  eachChunk([&](std::size_t i, std::size_t* row) { ++row[bucketOf(all[i])]; });
  std::size_t next = 0;
  for (std::size_t bucket = 0; bucket < buckets; ++bucket) {
    slab_start[bucket] = next;
    for (std::size_t c = 0; c < chunks; ++c)
      next += std::exchange(counts[c * buckets + bucket], next);
  }
  slab_start[buckets] = next;
  // Each row of counts now holds where its chunk's run of each bucket starts.
  eachChunk([&](std::size_t i, std::size_t* row) {
    sorted[row[bucketOf(all[i])]++] = all[i];
  });
}

/** Slab x of the voxelization: zeroes it, sums the trilinear weights W of the splats
 *  in [first, last) and turns them into the soft occupancy while the slab is in cache.
 *  Writes slab x only, in a fixed order; the weights are formed in double and summed in
 *  the precision of \a out. */
template <typename RealArray>
void accumulateSlab(const SpatialGrid& grid, int x, const Splat* first,
                    const Splat* last, double saturation, RealArray& out)
{
  using Real = typename RealArray::value_type;
  const int ny = grid.dims.y(), nz = grid.dims.z();
  const std::size_t slab = static_cast<std::size_t>(ny) * nz;
  std::fill_n(out.begin() + static_cast<std::ptrdiff_t>(x * slab), slab, Real(0));
  for (const Splat* s = first; s != last; ++s) {
    const double wx = s->base.x() == x ? 1.0 - s->frac.x() : s->frac.x();
    for (int dy = 0; dy < 2; ++dy) {
      const int y = s->base.y() + dy;
      if (y < 0 || y >= ny)
        continue;
      const double wxy = wx * (dy ? s->frac.y() : 1.0 - s->frac.y());
      for (int dz = 0; dz < 2; ++dz) {
        const int z = s->base.z() + dz;
        if (z >= 0 && z < nz)
          out[grid.flatIndex(x, y, z)] +=
              static_cast<Real>(wxy * (dz ? s->frac.z() : 1.0 - s->frac.z()));
      }
    }
  }
  const std::size_t end = (static_cast<std::size_t>(x) + 1) * slab;
  for (std::size_t i = static_cast<std::size_t>(x) * slab; i < end; ++i) {
    const double w = out[i];
    if (w <= 0.0)
      out[i] = Real(0);
    else
      out[i] = static_cast<Real>(
          saturation > 0.0 ? -saturation * std::expm1(-w / saturation) : w);
  }
}

} // namespace

int nextFftFriendlySize(int n)
{
  if (n > (1 << 30))
    throw InvalidArgument("nextFftFriendlySize: " + std::to_string(n) +
                          " is too large");
  for (int m = std::max(n, 1);; ++m) {
    int r = m;
    for (int f : {2, 3, 5})
      while (r % f == 0)
        r /= f;
    if (r == 1)
      return m;
  }
}

SpatialGrid makeSpatialGrid(const Eigen::Matrix3Xd& points,
                            const SpatialGridParameters& parameters)
{
  const SpatialGridParameters& p = parameters;
  if (!std::isfinite(p.voxel_size) || p.voxel_size < 0.0)
    throw InvalidArgument(
        "spatial voxel_size must be finite and >= 0 (0 = use grid_size)");
  if (p.voxel_size == 0.0 && (p.grid_size < kMinGridSize || p.grid_size > kMaxGridSize))
    throw InvalidArgument("spatial grid_size must be in [8, 1024], got " +
                          std::to_string(p.grid_size));
  if (!std::isfinite(p.padding) || p.padding < 0.0)
    throw InvalidArgument("spatial padding must be finite and >= 0");
  if (!std::isfinite(p.min_margin) || p.min_margin < 0.0)
    throw InvalidArgument("spatial min_margin must be finite and >= 0");

  Eigen::Vector3d lo =
      Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    if (!points.col(i).allFinite())
      continue;
    lo = lo.cwiseMin(points.col(i));
    hi = hi.cwiseMax(points.col(i));
  }
  if (!(lo.array() <= hi.array()).all())
    throw InvalidArgument("makeSpatialGrid: the point set has no finite points");

  const Eigen::Array3d extent = (hi - lo).array();
  const Eigen::Array3d covered =
      extent + 2.0 * (p.padding * extent).max(Eigen::Array3d::Constant(p.min_margin));

  double voxel = p.voxel_size;
  if (voxel == 0.0) {
    // The longest axis gets exactly nextFftFriendlySize(grid_size) voxels, two of which
    // are the splat margin (one per side).
    const int n = nextFftFriendlySize(p.grid_size);
    voxel = covered.maxCoeff() / (n - 2);
    if (!(voxel > 0.0) || !std::isfinite(voxel))
      throw InvalidArgument("makeSpatialGrid: all points coincide; set voxel_size or "
                            "min_margin");
  }

  SpatialGrid grid;
  grid.voxel_size = voxel;
  for (int a = 0; a < 3; ++a) {
    // The tolerance keeps an exact multiple (the longest axis) from rounding up by one.
    const double needed = std::ceil(covered[a] / voxel - 1e-9) + 2.0;
    if (!(needed <= kMaxGridSize))
      throw InvalidArgument("makeSpatialGrid: voxel_size " + std::to_string(voxel) +
                            " needs more than 1024 voxels along an axis");
    grid.dims[a] =
        nextFftFriendlySize(std::max(kMinGridSize, static_cast<int>(needed)));
  }
  grid.origin = 0.5 * (lo + hi) - 0.5 * grid.extent();
  return grid;
}

namespace {

/** voxelize into a volume of the precision of \a Volume. */
template <typename Volume>
Volume voxelizeAs(const SpatialGrid& grid, const Eigen::Matrix3Xd& points,
                  const SpatialVoxelParameters& parameters)
{
  checkGrid(grid, "voxelize");
  const int threads = resolveThreads(parameters.num_threads);
  const double saturation = parameters.saturation;
  if (!std::isfinite(saturation) || saturation < 0.0)
    throw InvalidArgument("voxelize: saturation must be finite and >= 0");
  const int nx = grid.dims.x();
  const std::size_t count = static_cast<std::size_t>(points.cols());
  // Left uninitialized: every footprint read is written first.
  const std::unique_ptr<Splat[]> all(new Splat[count]), sorted(new Splat[count]);
  const std::unique_ptr<char[]> inside(new char[count]);
  std::vector<std::size_t> slab_start(static_cast<std::size_t>(nx) + 2);
  Volume volume;
  volume.grid = grid;
  volume.values.resize(grid.size());
  // Footprints, the counting sort, then the slabs: slab x sums the splats of lower x
  // index x-1 and x (buckets x and x+1) alone and in a fixed order, so the result does
  // not depend on the thread count.
  detail::parallelFor(points.cols(), 1024, threads,
                      [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
                        pointFootprints(grid, points, all.get(), inside.get(), first,
                                        last);
                      });
  sortBySlab(all.get(), inside.get(), count, sorted.get(), slab_start, threads);
  detail::parallelFor(
      nx, 4, threads, [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
        for (std::ptrdiff_t x = first; x < last; ++x)
          accumulateSlab(grid, static_cast<int>(x), sorted.get() + slab_start[x],
                         sorted.get() + slab_start[x + 2], saturation, volume.values);
      });
  return volume;
}

/** computeSpectrum into a spectrum of the precision of \a Spectrum. */
template <typename Spectrum, typename Volume>
Spectrum spectrumOf(const Volume& volume, int num_threads)
{
  const int threads = resolveThreads(num_threads);
  checkVolume(volume, "computeSpectrum");
  Spectrum spectrum;
  spectrum.grid = volume.grid;
  spectrum.coefficients.resize(static_cast<std::size_t>(volume.grid.dims.x()) *
                               volume.grid.dims.y() * spectrum.halfZ());
  detail::forwardFft3d(volume.grid.dims, volume.values.data(),
                       spectrum.coefficients.data(), threads);
  return spectrum;
}

} // namespace

SpatialVolume voxelize(const SpatialGrid& grid, const Eigen::Matrix3Xd& points,
                       const SpatialVoxelParameters& parameters)
{
  return voxelizeAs<SpatialVolume>(grid, points, parameters);
}

SpatialSpectrum computeSpectrum(const SpatialVolume& volume, int num_threads)
{
  return spectrumOf<SpatialSpectrum>(volume, num_threads);
}

namespace {

/** c_i = f_i conj(g_i) scale / |f_i conj(g_i)|^(1/2) (0 where the product is 0) on
 *  interleaved (re, im) values; \a c may be \a g. Inlined into the two clones below. */
template <typename Real>
[[gnu::always_inline]] inline void quarterWhitenedLoop(const Real* f, const Real* g,
                                                       Real* c, std::size_t count,
                                                       Real scale)
{
#pragma GCC ivdep
  for (std::size_t i = 0; i < count; ++i) {
    const Real fr = f[2 * i], fi = f[2 * i + 1], gr = g[2 * i], gi = g[2 * i + 1];
    const Real re = fr * gr + fi * gi;
    const Real im = fi * gr - fr * gi;
    const Real n = re * re + im * im;
    const Real w = scale / std::sqrt(std::sqrt(n)); // inf where n is 0: not taken
    const Real kept = n > Real(0) ? w : Real(0);
    c[2 * i] = re * kept;
    c[2 * i + 1] = im * kept;
  }
}

/** quarterWhitenedLoop in double and in float on plain arrays, compiled for AVX2 and
 *  the default (no FMA: the bits of the scalar loop). */
[[gnu::target_clones("avx2", "default")]] void
quarterWhitenedProduct(const double* f, const double* g, double* c, std::size_t count,
                       double scale)
{
  quarterWhitenedLoop(f, g, c, count, scale);
}

[[gnu::target_clones("avx2", "default")]] void
quarterWhitenedProduct(const float* f, const float* g, float* c, std::size_t count,
                       float scale)
{
  quarterWhitenedLoop(f, g, c, count, scale);
}

/** C[i] = F[i] conj(G[i]) * scale / |F[i] conj(G[i])|^whitening (0 where the product
 *  is 0) for i in [first, first + count); \a C may be \a G. The whitening case is
 *  chosen once per run, not per element; |c|^whitening comes from the squared
 *  magnitude (std::abs calls the slow hypot). */
template <typename Real>
void crossPowerRun(const std::complex<Real>* F, const std::complex<Real>* G,
                   std::complex<Real>* C, std::size_t first, std::size_t count,
                   Real scale, double whitening)
{
  const auto cross = [&](std::size_t i) {
    const std::complex<Real> f = F[i], g = G[i];
    return std::complex<Real>{f.real() * g.real() + f.imag() * g.imag(),
                              f.imag() * g.real() - f.real() * g.imag()};
  };
  const auto each = [&](const auto& magnitude) {
    for (std::size_t i = first; i < first + count; ++i) {
      const std::complex<Real> c = cross(i);
      const Real n = c.real() * c.real() + c.imag() * c.imag();
      C[i] = c * (n > Real(0) ? scale / magnitude(n) : Real(0));
    }
  };
  if (whitening == 0.0)
    for (std::size_t i = first; i < first + count; ++i)
      C[i] = cross(i) * scale;
  else if (whitening == 0.5)
    quarterWhitenedProduct(reinterpret_cast<const Real*>(F + first),
                           reinterpret_cast<const Real*>(G + first),
                           reinterpret_cast<Real*>(C + first), count, scale);
  else if (whitening == 1.0)
    each([](Real n) { return std::sqrt(n); });
  else
    each([whitening](Real n) {
      return std::pow(n, static_cast<Real>(0.5 * whitening));
    });
}

/** The number of stored coefficients of two spectra that can be correlated.
 *  \throws InvalidArgument when their grids or sizes do not match. */
template <typename Spectrum>
std::size_t checkedSpectrumSize(const Spectrum& target, const Spectrum& source)
{
  checkGrid(target.grid, "correlateSpectra (target)");
  checkGrid(source.grid, "correlateSpectra (source)");
  if (target.grid.dims != source.grid.dims ||
      std::abs(target.grid.voxel_size - source.grid.voxel_size) >
          1e-9 * target.grid.voxel_size)
    throw InvalidArgument("correlateSpectra: target and source grids differ in dims or "
                          "voxel size");
  const std::size_t m = static_cast<std::size_t>(target.grid.dims.x()) *
                        target.grid.dims.y() * target.halfZ();
  if (target.coefficients.size() != m || source.coefficients.size() != m)
    throw InvalidArgument("correlateSpectra: spectrum size does not match its grid");
  return m;
}

/** C = F conj(G) / N written into \a out (which may alias \a source), divided by
 *  |F conj(G)|^whitening, then the c2r (unnormalized; 1/N makes the output the plain
 *  sum when whitening is 0). The product of each run is formed inside the inverse
 *  transform's loop over rows, just before the run is transformed. */
template <typename Volume, typename Spectrum>
Volume correlateInto(const Spectrum& target, const Spectrum& source,
                     decltype(Spectrum::coefficients)& out, int num_threads,
                     double whitening = 0.0)
{
  using Complex = typename decltype(Spectrum::coefficients)::value_type;
  using Real = typename Complex::value_type;
  const int threads = resolveThreads(num_threads);
  out.resize(checkedSpectrumSize(target, source));
  const Real scale = static_cast<Real>(1.0 / static_cast<double>(target.grid.size()));
  const Complex* F = target.coefficients.data();
  const Complex* G = source.coefficients.data();
  Complex* C = out.data();
  Volume correlation;
  correlation.grid = target.grid;
  correlation.grid.origin = target.grid.origin - source.grid.origin;
  correlation.values.resize(target.grid.size());
  detail::inverseFft3d(target.grid.dims, C, correlation.values.data(), threads,
                       [=](std::size_t first, std::size_t count) {
                         crossPowerRun(F, G, C, first, count, scale, whitening);
                       });
  return correlation;
}

} // namespace

SpatialVolume correlateSpectra(const SpatialSpectrum& target,
                               const SpatialSpectrum& source, int num_threads)
{
  SpatialComplexArray product;
  return correlateInto<SpatialVolume>(target, source, product, num_threads);
}

namespace {

/** correlateSpectraWhitened in the precision of \a Volume and \a Spectrum. */
template <typename Volume, typename Spectrum>
Volume whitenedCorrelation(const Spectrum& target, Spectrum&& source, double exponent,
                           int num_threads)
{
  if (!(exponent >= 0.0 && exponent <= 1.0))
    throw InvalidArgument("correlateSpectraWhitened: exponent must be in [0, 1]");
  Spectrum consumed = std::move(source);
  return correlateInto<Volume>(target, consumed, consumed.coefficients, num_threads,
                               exponent);
}

} // namespace

SpatialVolume correlateSpectraWhitened(const SpatialSpectrum& target,
                                       SpatialSpectrum&& source, double exponent,
                                       int num_threads)
{
  return whitenedCorrelation<SpatialVolume>(target, std::move(source), exponent,
                                            num_threads);
}

namespace detail {

SpatialSpectrumF singlePrecision(const SpatialSpectrum& spectrum)
{
  SpatialSpectrumF single;
  single.grid = spectrum.grid;
  single.coefficients.resize(spectrum.coefficients.size());
  std::transform(spectrum.coefficients.begin(), spectrum.coefficients.end(),
                 single.coefficients.begin(),
                 [](const std::complex<double>& c) { return std::complex<float>(c); });
  return single;
}

SpatialVolumeF voxelizeSingle(const SpatialGrid& grid, const Eigen::Matrix3Xd& points,
                              const SpatialVoxelParameters& parameters)
{
  return voxelizeAs<SpatialVolumeF>(grid, points, parameters);
}

SpatialSpectrumF computeSpectrum(const SpatialVolumeF& volume, int num_threads)
{
  return spectrumOf<SpatialSpectrumF>(volume, num_threads);
}

SpatialVolumeF correlateSpectraWhitened(const SpatialSpectrumF& target,
                                        SpatialSpectrumF&& source, double exponent,
                                        int num_threads)
{
  return whitenedCorrelation<SpatialVolumeF>(target, std::move(source), exponent,
                                             num_threads);
}

} // namespace detail

} // namespace pcl::phaser
