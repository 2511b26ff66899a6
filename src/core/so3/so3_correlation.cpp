/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "so3/so3_correlation.h"
#include "so3/wigner.h"
#include "support/error.h"
#include "support/fftw_support.h"
#include "support/instance_cache.h"
#include "support/parallel.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <utility>
#include <vector>

namespace pcl::phaser {

using Complex = std::complex<double>;

namespace {

/** Correlations of bandwidth below this run on the calling thread. */
constexpr int kMinParallelBandwidth = 64;

/** F(l, m) for any order, from the stored m >= 0 half of a real function's spectrum. */
inline Complex coefficient(const SphericalSpectrum& F, int l, int m)
{
  if (m >= 0)
    return F(l, m);
  const Complex c = std::conj(F(l, -m));
  return (m % 2) ? -c : c;
}

inline int wrap(int i, int n)
{
  return ((i % n) + n) % n;
}

void checkSpectrum(const SphericalSpectrum& F, int B, const char* what)
{
  if (F.rows() != B || F.cols() != B)
    throw InvalidArgument(std::string(what) + " spectrum must be " + std::to_string(B) +
                          " x " + std::to_string(B) + ", got " +
                          std::to_string(F.rows()) + " x " + std::to_string(F.cols()));
}

/** Per-thread scratch of the Wigner stage: three d rows and two accumulators, split
 * into real and imaginary parts so the inner loops vectorize. */
struct WignerScratch {
  explicit WignerScratch(int J, int B)
      : d0(J)
      , d1(J)
      , d2(J)
      , acc1_re(J)
      , acc1_im(J)
      , acc2_re(J)
      , acc2_im(J)
      , c1(B)
      , c2(B)
  {
  }
  std::vector<double> d0, d1, d2, acc1_re, acc1_im, acc2_re, acc2_im;
  std::vector<Complex> c1, c2;
};

/** The Wigner stage for one order pair (m', m): runs the l-recurrence over all beta_j
 *  (j < J) and accumulates the two half-plane sums. Plain arrays only, so the function
 * can be compiled twice and picked at run time: AVX2 where the CPU has it (4 doubles
 * per instruction), SSE2 elsewhere. No -march=native anywhere (see the integration
 * notes). The choice depends on the machine only, never on the thread count. */
[[gnu::target_clones("avx2", "default")]] void
wignerAccumulate(const WignerStepTable& steps, int L, int B, int J, int mp, int m,
                 const double* __restrict cb, const double* __restrict c1,
                 const double* __restrict c2, double* __restrict d0,
                 double* __restrict d1, double* __restrict d2, double* __restrict a1r,
                 double* __restrict a1i, double* __restrict a2r, double* __restrict a2i)
{
  double* dprev = d0;
  double* dpp = d1;
  double* dnext = d2;
  for (int j = 0; j < J; ++j) {
    a1r[j] = a1i[j] = a2r[j] = a2i[j] = 0.0;
    dpp[j] =
        0.0; // d^{L-1} := 0 (its coefficient b is 0 too, but 0 * garbage may be NaN)
  }
  for (int l = L; l < B; ++l) {
    const double c1r = c1[2 * l], c1i = c1[2 * l + 1];
    const double c2r = c2[2 * l], c2i = c2[2 * l + 1];
    for (int j = 0; j < J; ++j) {
      const double d = dprev[j];
      a1r[j] += c1r * d;
      a1i[j] += c1i * d;
      a2r[j] += c2r * d;
      a2i[j] += c2i * d;
    }
    if (l + 1 < B) {
      const WignerStep st = steps.step(l, mp, m);
      for (int j = 0; j < J; ++j)
        dnext[j] = (st.a * cb[j] + st.ac) * dprev[j] - st.b * dpp[j];
      double* tmp = dpp; // dpp <- d^l, dprev <- d^{l+1}
      dpp = dprev;
      dprev = dnext;
      dnext = tmp;
    }
  }
}

/** The l-recurrence of the exact evaluation for one order pair, for K rotations at once
 *  (their cos beta in \a cb), shared by P coefficient sequences (c holds P rows of B
 *  complex values): acc_p,k = sum_l c_p,l d^l(beta_k), split into real and imaginary
 *  parts (P rows of K). Each sequence sees the same operations in the same order as
 *  if it were alone. Dispatched like wignerAccumulate. */
[[gnu::target_clones("avx2", "default")]] void
evaluateAccumulate(const WignerStepTable& steps, int L, int B, int K, int P, int mp,
                   int m, const double* __restrict cb, const double* __restrict c,
                   double* __restrict d0, double* __restrict d1, double* __restrict d2,
                   double* __restrict acc_re, double* __restrict acc_im)
{
  double* dprev = d0;
  double* dpp = d1;
  double* dnext = d2;
  for (int k = 0; k < K; ++k)
    dpp[k] = 0.0;
  for (int i = 0; i < P * K; ++i)
    acc_re[i] = acc_im[i] = 0.0;
  for (int l = L; l < B; ++l) {
    for (int q = 0; q < P; ++q) {
      const double cr = c[2 * (q * B + l)], ci = c[2 * (q * B + l) + 1];
      double* __restrict ar = acc_re + q * K;
      double* __restrict ai = acc_im + q * K;
      for (int k = 0; k < K; ++k) {
        ar[k] += cr * dprev[k];
        ai[k] += ci * dprev[k];
      }
    }
    if (l + 1 < B) {
      const WignerStep st = steps.step(l, mp, m);
      for (int k = 0; k < K; ++k)
        dnext[k] = (st.a * cb[k] + st.ac) * dprev[k] - st.b * dpp[k];
      double* tmp = dpp;
      dpp = dprev;
      dprev = dnext;
      dnext = tmp;
    }
  }
}

/** Where So3Correlator::correlate writes: \a rows beta slices of N x nh complex values
 *  (N = 2 Bo, nh = Bo + 1) at \a T; the Wigner recurrence runs over the beta rows
 *  j < J; B is the input bandwidth. */
struct SliceLayout {
  int B = 0, N = 0, J = 0, rows = 0;
  std::size_t nh = 0, slice = 0;
  Complex* T = nullptr;
};

/** The So3Correlator tables the Wigner stage reads (beta_j for j < Bo). */
struct WignerTables {
  const WignerStepTable& steps;
  const std::vector<double>& log_factorials;
  const std::vector<double>& cos_beta;
  const std::vector<double>& log_cos_half;
  const std::vector<double>& log_sin_half;
};

/** Zeroes what the Wigner stage does not write: orders |m'| >= B (rows p in [B, N-B])
 *  and m >= B (columns q in [B, Bo]), Nyquist included, in beta slices [first, last).
 */
void zeroUnwrittenOrders(const SliceLayout& g, int first, int last)
{
  for (int s = first; s < last; ++s)
    for (int p = 0; p < g.N; ++p) {
      Complex* row = g.T + s * g.slice + p * g.nh;
      const bool unused_row = p >= g.B && p <= g.N - g.B;
      std::fill(row + (unused_row ? 0 : g.B), row + g.nh, Complex(0.0));
    }
}

/** The Wigner stage for order m and every m': the two half-plane sums over l, written
 *  (conjugated) into column m of rows m' and -m' of every beta slice. */
void wignerOrder(const SphericalSpectrum& target, const SphericalSpectrum& source,
                 int m, const WignerTables& tables, const SliceLayout& g,
                 WignerScratch& w)
{
  const int B = g.B, N = g.N, J = g.J;
  for (int mp = -(B - 1); mp < B; ++mp) {
    const int L = std::max(std::abs(mp), m);
    for (int l = L; l < B; ++l) {
      const Complex h = source(l, m);
      w.c1[l] = std::conj(coefficient(target, l, mp)) * h;
      const Complex c2 = std::conj(coefficient(target, l, -mp)) * h;
      w.c2[l] = ((l - m) % 2) ? -c2 : c2;
    }
    const WignerStart start = wignerStart(mp, m, tables.log_factorials);
    for (int j = 0; j < J; ++j)
      w.d0[j] = start.value(tables.log_cos_half[j], tables.log_sin_half[j]);
    wignerAccumulate(tables.steps, L, B, J, mp, m, tables.cos_beta.data(),
                     reinterpret_cast<const double*>(w.c1.data()),
                     reinterpret_cast<const double*>(w.c2.data()), w.d0.data(),
                     w.d1.data(), w.d2.data(), w.acc1_re.data(), w.acc1_im.data(),
                     w.acc2_re.data(), w.acc2_im.data());
    const double* a1r = w.acc1_re.data();
    const double* a1i = w.acc1_im.data();
    const double* a2r = w.acc2_re.data();
    const double* a2i = w.acc2_im.data();
    // c2r computes sum T e^{+i...}: feed conj(S) to get the e^{-i...} sum of the spec.
    const int p1 = wrap(mp, N), p2 = wrap(-mp, N);
    for (int j = 0; j < J; ++j) {
      g.T[j * g.slice + p1 * g.nh + m] = Complex(a1r[j], -a1i[j]);
      if (N - 1 - j < g.rows)
        g.T[(N - 1 - j) * g.slice + p2 * g.nh + m] = Complex(a2r[j], -a2i[j]);
    }
  }
}

/** One in-place N x N c2r FFT per beta slice in [first, last). */
void inverseSlices(const SliceLayout& g, fftw_plan slice_c2r, int first, int last)
{
  for (int s = first; s < last; ++s) {
    fftw_complex* in = reinterpret_cast<fftw_complex*>(g.T + s * g.slice);
    fftw_execute_dft_c2r(slice_c2r, in, reinterpret_cast<double*>(in));
  }
}

} // namespace

// ---------------------------------------------------------------------------------------
struct So3Correlator::Plan {
  detail::FftwPlan slice_c2r; // one in-place N x N c2r, run once per beta sample
};

std::shared_ptr<const So3Correlator> So3Correlator::instance(int bandwidth,
                                                             int output_bandwidth)
{
  checkBandwidth(bandwidth);
  if (output_bandwidth == 0)
    output_bandwidth = bandwidth;
  static detail::InstanceCache<std::pair<int, int>, So3Correlator> cache;
  return cache.get({bandwidth, output_bandwidth}, [&] {
    return std::make_shared<const So3Correlator>(bandwidth, output_bandwidth);
  });
}

So3Correlator::So3Correlator(int bandwidth, int output_bandwidth)
    : bandwidth_(bandwidth)
    , output_bandwidth_(output_bandwidth ? output_bandwidth : bandwidth)
    , steps_(wignerStepTable(bandwidth))
    , plan_(std::make_unique<Plan>())
{
  checkBandwidth(bandwidth_);
  checkBandwidth(output_bandwidth_, "output bandwidth");
  if (output_bandwidth_ < bandwidth_)
    throw InvalidArgument("output bandwidth must be >= bandwidth");
  const int Bo = output_bandwidth_;
  const int N = 2 * Bo;
  for (int j = 0; j < Bo; ++j) {
    const double beta = M_PI * (2 * j + 1) / (4.0 * Bo);
    cos_beta_.push_back(std::cos(beta));
    log_cos_half_.push_back(std::log(std::cos(0.5 * beta)));
    log_sin_half_.push_back(std::log(std::sin(0.5 * beta)));
  }
  log_factorials_ = logFactorials(2 * bandwidth_ + 1);
  // Each slice is N x (Bo+1) complex = N x 2(Bo+1) padded reals; its byte size
  // 32 Bo (Bo+1) is a multiple of 64, so every slice keeps the planning alignment.
  auto slice =
      detail::fftwAllocate<fftw_complex>(static_cast<std::size_t>(N) * (Bo + 1));
  std::lock_guard<std::mutex> lock(detail::fftwPlannerMutex());
  plan_->slice_c2r = detail::FftwPlan(fftw_plan_dft_c2r_2d(
      N, N, slice.get(), reinterpret_cast<double*>(slice.get()), detail::kFftwFlags));
}

So3Correlator::~So3Correlator() = default;

So3CorrelationGrid So3Correlator::correlate(const SphericalSpectrum& target,
                                            const SphericalSpectrum& source,
                                            int num_threads, int beta_rows) const
{
  const int B = bandwidth_;
  const int Bo = output_bandwidth_;
  const int N = 2 * Bo;
  if (beta_rows < 0)
    throw InvalidArgument("So3Correlator::correlate: beta_rows must be >= 0");
  const int rows = beta_rows == 0 ? N : std::min(beta_rows, N);
  checkSpectrum(target, B, "target");
  checkSpectrum(source, B, "source");
  // Below B = 64 (the orientation histograms' B = 32: about 1 ms of work) the calling
  // thread does it all: a parked worker would cost more than the work.
  num_threads = B < kMinParallelBandwidth ? 1 : std::max(1, num_threads);

  // beta_j for j < Bo; the mirrored half (rows N-1-j) comes from d(pi - beta). With a
  // tilt limit the recurrence runs over the rows j < min(rows, Bo) and the mirrored
  // rows it yields are kept only when they are below \a rows too.
  SliceLayout layout;
  layout.B = B;
  layout.N = N;
  layout.J = std::min(Bo, rows);
  layout.rows = rows;
  layout.nh = Bo + 1;
  layout.slice = static_cast<std::size_t>(N) * layout.nh;

  So3CorrelationGrid grid;
  grid.output_bandwidth_ = Bo;
  grid.beta_rows_ = rows;
  grid.row_stride_ = 2 * layout.nh;
  // Only the computed rows are stored (operator() gives -infinity beyond them).
  grid.data_ =
      static_cast<double*>(fftw_malloc(sizeof(fftw_complex) * layout.slice * rows));
  if (!grid.data_)
    throw std::bad_alloc();
  layout.T = reinterpret_cast<Complex*>(grid.data_);

  const WignerTables tables{*steps_, log_factorials_, cos_beta_, log_cos_half_,
                            log_sin_half_};
  // Zeroing and the Wigner stage write disjoint entries (orders below B are the
  // Wigner stage's), so they share one loop; the slices' FFTs need both. Four orders
  // per chunk: neighbouring orders write neighbouring columns of every slice, which
  // share cache lines (benchmarks.md 11.19).
  detail::parallelFor(std::max(rows, B), 4, num_threads,
                      [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
                        for (int k = static_cast<int>(first); k < last; ++k) {
                          if (k < rows)
                            zeroUnwrittenOrders(layout, k, k + 1);
                          if (k < B) {
                            WignerScratch w(layout.J, B);
                            wignerOrder(target, source, k, tables, layout, w);
                          }
                        }
                      });
  detail::parallelFor(rows, 1, num_threads,
                      [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
                        inverseSlices(layout, plan_->slice_c2r.get(),
                                      static_cast<int>(first), static_cast<int>(last));
                      });
  return grid;
}

// ---------------------------------------------------------------------------------------
std::vector<std::vector<double>>
evaluateCorrelations(const std::vector<SpectrumPair>& pairs,
                     const std::vector<Eigen::Matrix3d>& rotations, int num_threads)
{
  if (pairs.empty())
    return {};
  for (const SpectrumPair& pair : pairs)
    if (!pair.target || !pair.source)
      throw InvalidArgument("evaluateCorrelations: a spectrum pair is incomplete");
  const int B = static_cast<int>(pairs.front().source->rows());
  checkBandwidth(B);
  for (const SpectrumPair& pair : pairs) {
    checkSpectrum(*pair.target, B, "target");
    checkSpectrum(*pair.source, B, "source");
  }
  const int P = static_cast<int>(pairs.size());
  const int K = static_cast<int>(rotations.size());
  std::vector<EulerZYZ> euler(K);
  std::vector<double> cb(K), lc(K), ls(K);
  for (int k = 0; k < K; ++k) {
    euler[k] = eulerFromRotation(rotations[k]);
    cb[k] = std::cos(euler[k].beta);
    lc[k] = std::log(std::cos(0.5 * euler[k].beta));
    ls[k] = std::log(std::sin(0.5 * euler[k].beta));
  }
  const std::vector<double> lf = logFactorials(2 * B + 1);
  const std::shared_ptr<const WignerStepTable> steps = wignerStepTable(B);
  // e^{-i m' alpha_k} for every order m' and rotation k, once: inside the loop over
  // (m, m') it would be B times as many sincos.
  std::vector<Complex> turn_table(static_cast<std::size_t>(2 * B - 1) * K);
  for (int mp = -(B - 1); mp < B; ++mp)
    for (int k = 0; k < K; ++k)
      turn_table[static_cast<std::size_t>(mp + B - 1) * K + k] =
          std::polar(1.0, -mp * euler[k].alpha);
  // Per-order partial sums, reduced in a fixed order: identical for any thread count.
  const std::size_t PK = static_cast<std::size_t>(P) * K;
  std::vector<double> partial(static_cast<std::size_t>(B) * PK, 0.0);

  detail::parallelFor(
      B, 1, num_threads, [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
        std::vector<double> d0(K), d1(K), d2(K), acc_re(PK), acc_im(PK);
        std::vector<Complex> sum_mp(PK), c(static_cast<std::size_t>(P) * B);
        for (int m = static_cast<int>(first); m < last; ++m) {
          std::fill(sum_mp.begin(), sum_mp.end(), Complex(0.0));
          for (int mp = -(B - 1); mp < B; ++mp) {
            const int L = std::max(std::abs(mp), m);
            const WignerStart start = wignerStart(mp, m, lf);
            for (int k = 0; k < K; ++k)
              d0[k] = start.value(lc[k], ls[k]);
            for (int q = 0; q < P; ++q)
              for (int l = L; l < B; ++l)
                c[static_cast<std::size_t>(q) * B + l] =
                    std::conj(coefficient(*pairs[q].target, l, mp)) *
                    (*pairs[q].source)(l, m);
            evaluateAccumulate(*steps, L, B, K, P, mp, m, cb.data(),
                               reinterpret_cast<const double*>(c.data()), d0.data(),
                               d1.data(), d2.data(), acc_re.data(), acc_im.data());
            const Complex* turn = &turn_table[static_cast<std::size_t>(mp + B - 1) * K];
            for (std::size_t i = 0; i < PK; ++i)
              sum_mp[i] += turn[i % K] * Complex(acc_re[i], acc_im[i]);
          }
          const double eps = (m == 0) ? 1.0 : 2.0;
          for (std::size_t i = 0; i < PK; ++i)
            partial[static_cast<std::size_t>(m) * PK + i] =
                eps * (std::polar(1.0, -m * euler[i % K].gamma) * sum_mp[i]).real();
        }
      });
  std::vector<std::vector<double>> value(P, std::vector<double>(K, 0.0));
  for (int m = 0; m < B; ++m)
    for (int q = 0; q < P; ++q)
      for (int k = 0; k < K; ++k)
        value[q][k] += partial[static_cast<std::size_t>(m) * PK +
                               static_cast<std::size_t>(q) * K + k];
  return value;
}

std::vector<double> evaluateCorrelation(const SphericalSpectrum& target,
                                        const SphericalSpectrum& source,
                                        const std::vector<Eigen::Matrix3d>& rotations,
                                        int num_threads)
{
  return std::move(
      evaluateCorrelations({SpectrumPair{&target, &source}}, rotations, num_threads)
          .front());
}

} // namespace pcl::phaser
