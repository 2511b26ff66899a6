/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "so3/so3_correlation.h"
#include "so3/wigner.h"
#include "support/buffer_pool.h"
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

/** Correlations of bandwidth below this (about 1 ms of work at B = 32) run on the
 *  calling thread: waking a parked worker would cost more. */
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

/** Per-thread scratch of the Wigner stage: three d rows, the two coefficient
 *  sequences (B each) and their two accumulators (J each), real and imaginary parts
 *  apart so the inner loops vectorize. */
struct WignerScratch {
  explicit WignerScratch(int J, int B)
      : d0(J)
      , d1(J)
      , d2(J)
      , acc_re(2 * J)
      , acc_im(2 * J)
      , c(2 * B)
  {
  }
  std::vector<double> d0, d1, d2, acc_re, acc_im;
  std::vector<Complex> c;
};

/** The l-recurrence for one order pair (m', m) at K values of beta (their cosines in
 *  \a cb), shared by P coefficient sequences (c holds P rows of B complex values):
 *  acc_p,k = sum_l c_p,l d^l(beta_k), real and imaginary parts apart (P rows of K).
 *  Each sequence sees the same operations in the same order as if it were alone.
 *  Plain arrays, so the function is compiled twice and picked at run time (AVX2 where
 *  the CPU has it, no FMA): the choice depends on the machine only. */
[[gnu::target_clones("avx2", "default")]] void
accumulateDegrees(const WignerStepTable& steps, int L, int B, int K, int P, int mp,
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
void zeroUnwrittenOrders(const SliceLayout& layout, int first, int last)
{
  for (int s = first; s < last; ++s)
    for (int p = 0; p < layout.N; ++p) {
      Complex* row = layout.T + s * layout.slice + p * layout.nh;
      const bool unused_row = p >= layout.B && p <= layout.N - layout.B;
      std::fill(row + (unused_row ? 0 : layout.B), row + layout.nh, Complex(0.0));
    }
}

/** The Wigner stage for order m and every m': the two half-plane sums over l, written
 *  (conjugated) into column m of rows m' and -m' of every beta slice. */
void wignerOrder(const SphericalSpectrum& target, const SphericalSpectrum& source,
                 int m, const WignerTables& tables, const SliceLayout& layout,
                 WignerScratch& scratch)
{
  const int B = layout.B, N = layout.N, J = layout.J;
  for (int mp = -(B - 1); mp < B; ++mp) {
    const int L = std::max(std::abs(mp), m);
    for (int l = L; l < B; ++l) {
      const Complex h = source(l, m);
      scratch.c[l] = std::conj(coefficient(target, l, mp)) * h;
      const Complex c2 = std::conj(coefficient(target, l, -mp)) * h;
      scratch.c[B + l] = ((l - m) % 2) ? -c2 : c2;
    }
    const WignerStart start = wignerStart(mp, m, tables.log_factorials);
    for (int j = 0; j < J; ++j)
      scratch.d0[j] = start.value(tables.log_cos_half[j], tables.log_sin_half[j]);
    accumulateDegrees(tables.steps, L, B, J, 2, mp, m, tables.cos_beta.data(),
                      reinterpret_cast<const double*>(scratch.c.data()),
                      scratch.d0.data(), scratch.d1.data(), scratch.d2.data(),
                      scratch.acc_re.data(), scratch.acc_im.data());
    const double* a1r = scratch.acc_re.data();
    const double* a1i = scratch.acc_im.data();
    const double* a2r = scratch.acc_re.data() + J;
    const double* a2i = scratch.acc_im.data() + J;
    // c2r computes sum T e^{+i...}: feed conj(S) to get the e^{-i...} sum of the spec.
    const int p1 = wrap(mp, N), p2 = wrap(-mp, N);
    for (int j = 0; j < J; ++j) {
      layout.T[j * layout.slice + p1 * layout.nh + m] = Complex(a1r[j], -a1i[j]);
      if (N - 1 - j < layout.rows)
        layout.T[(N - 1 - j) * layout.slice + p2 * layout.nh + m] =
            Complex(a2r[j], -a2i[j]);
    }
  }
}

/** Every beta slice's coefficients: zeroing and the Wigner stage write disjoint
 *  entries (orders below B are the Wigner stage's), so they share one loop. Four
 *  orders per chunk: neighbouring orders write neighbouring columns of every slice,
 *  which share cache lines. */
void wignerStage(const SphericalSpectrum& target, const SphericalSpectrum& source,
                 const WignerTables& tables, const SliceLayout& layout, int num_threads)
{
  detail::parallelFor(std::max(layout.rows, layout.B), 4, num_threads,
                      [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
                        for (int k = static_cast<int>(first); k < last; ++k) {
                          if (k < layout.rows)
                            zeroUnwrittenOrders(layout, k, k + 1);
                          if (k < layout.B) {
                            WignerScratch scratch(layout.J, layout.B);
                            wignerOrder(target, source, k, tables, layout, scratch);
                          }
                        }
                      });
}

/** One in-place N x N c2r FFT per beta slice in [first, last). */
void inverseSlices(const SliceLayout& layout, fftw_plan slice_c2r, int first, int last)
{
  for (int s = first; s < last; ++s) {
    fftw_complex* in = reinterpret_cast<fftw_complex*>(layout.T + s * layout.slice);
    fftw_execute_dft_c2r(slice_c2r, in, reinterpret_cast<double*>(in));
  }
}

} // namespace

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
  // A slice's byte size 32 Bo (Bo+1) is a multiple of 64: every slice keeps the
  // planning alignment.
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
  num_threads = B < kMinParallelBandwidth ? 1 : std::max(1, num_threads);

  // beta_j for j < Bo; the mirrored half (rows N-1-j) comes from d(pi - beta). With a
  // tilt limit the recurrence runs over the rows j < min(rows, Bo) and the mirrored
  // rows it yields are kept only when they are below \a rows too.
  const std::size_t nh = Bo + 1;
  SliceLayout layout{B, N, std::min(Bo, rows), rows, nh, N * nh};

  So3CorrelationGrid grid;
  grid.output_bandwidth_ = Bo;
  grid.beta_rows_ = rows;
  grid.row_stride_ = 2 * layout.nh;
  // Only the computed rows are stored (operator() gives -infinity beyond them).
  const std::size_t bytes = sizeof(double) * 2 * layout.slice * rows;
  grid.data_ = std::unique_ptr<double[], So3CorrelationGrid::FftwFree>(
      static_cast<double*>(detail::bufferAcquire(bytes)), {bytes});
  layout.T = reinterpret_cast<Complex*>(grid.data_.get());

  const WignerTables tables{*steps_, log_factorials_, cos_beta_, log_cos_half_,
                            log_sin_half_};
  wignerStage(target, source, tables, layout, num_threads);
  detail::parallelFor(rows, 1, num_threads,
                      [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
                        inverseSlices(layout, plan_->slice_c2r.get(),
                                      static_cast<int>(first), static_cast<int>(last));
                      });
  return grid;
}

namespace {

/** The rotations of an exact evaluation as the recurrence reads them. */
struct EvaluationPoints {
  std::vector<EulerZYZ> euler;
  std::vector<double> cos_beta, log_cos_half, log_sin_half;
  /** e^{-i m' alpha_k} at [(m' + B - 1) K + k], computed once rather than in the loop
   *  over (m, m'), which would take B times as many sincos. */
  std::vector<Complex> turn;
};

EvaluationPoints evaluationPoints(const std::vector<Eigen::Matrix3d>& rotations, int B)
{
  const int K = static_cast<int>(rotations.size());
  EvaluationPoints points;
  points.euler.resize(K);
  points.cos_beta.resize(K);
  points.log_cos_half.resize(K);
  points.log_sin_half.resize(K);
  for (int k = 0; k < K; ++k) {
    points.euler[k] = eulerFromRotation(rotations[k]);
    points.cos_beta[k] = std::cos(points.euler[k].beta);
    points.log_cos_half[k] = std::log(std::cos(0.5 * points.euler[k].beta));
    points.log_sin_half[k] = std::log(std::sin(0.5 * points.euler[k].beta));
  }
  points.turn.resize(static_cast<std::size_t>(2 * B - 1) * K);
  for (int mp = -(B - 1); mp < B; ++mp)
    for (int k = 0; k < K; ++k)
      points.turn[static_cast<std::size_t>(mp + B - 1) * K + k] =
          std::polar(1.0, -mp * points.euler[k].alpha);
  return points;
}

/** The bandwidth B of \a pairs after checking that every spectrum is B x B. */
int checkedPairBandwidth(const std::vector<SpectrumPair>& pairs)
{
  for (const SpectrumPair& pair : pairs)
    if (!pair.target || !pair.source)
      throw InvalidArgument("evaluateCorrelations: a spectrum pair is incomplete");
  const int B = static_cast<int>(pairs.front().source->rows());
  checkBandwidth(B);
  for (const SpectrumPair& pair : pairs) {
    checkSpectrum(*pair.target, B, "target");
    checkSpectrum(*pair.source, B, "source");
  }
  return B;
}

/** The contribution of order m to every pair's C at every rotation, pair-major
 *  (P x K) into \a partial: the l-recurrence per m', shared by the pairs. */
void evaluateOrder(int m, const std::vector<SpectrumPair>& pairs,
                   const EvaluationPoints& points, const WignerStepTable& steps,
                   const std::vector<double>& log_factorials, double* partial)
{
  const int B = static_cast<int>(pairs.front().source->rows());
  const int P = static_cast<int>(pairs.size());
  const int K = static_cast<int>(points.euler.size());
  const std::size_t PK = static_cast<std::size_t>(P) * K;
  std::vector<double> d0(K), d1(K), d2(K), acc_re(PK), acc_im(PK);
  std::vector<Complex> sum_mp(PK, Complex(0.0)), c(static_cast<std::size_t>(P) * B);
  for (int mp = -(B - 1); mp < B; ++mp) {
    const int L = std::max(std::abs(mp), m);
    const WignerStart start = wignerStart(mp, m, log_factorials);
    for (int k = 0; k < K; ++k)
      d0[k] = start.value(points.log_cos_half[k], points.log_sin_half[k]);
    for (int q = 0; q < P; ++q)
      for (int l = L; l < B; ++l)
        c[static_cast<std::size_t>(q) * B + l] =
            std::conj(coefficient(*pairs[q].target, l, mp)) * (*pairs[q].source)(l, m);
    accumulateDegrees(steps, L, B, K, P, mp, m, points.cos_beta.data(),
                      reinterpret_cast<const double*>(c.data()), d0.data(), d1.data(),
                      d2.data(), acc_re.data(), acc_im.data());
    const Complex* turn = &points.turn[static_cast<std::size_t>(mp + B - 1) * K];
    for (std::size_t i = 0; i < PK; ++i)
      sum_mp[i] += turn[i % K] * Complex(acc_re[i], acc_im[i]);
  }
  const double eps = (m == 0) ? 1.0 : 2.0;
  for (std::size_t i = 0; i < PK; ++i)
    partial[i] =
        eps * (std::polar(1.0, -m * points.euler[i % K].gamma) * sum_mp[i]).real();
}

} // namespace

std::vector<std::vector<double>>
evaluateCorrelations(const std::vector<SpectrumPair>& pairs,
                     const std::vector<Eigen::Matrix3d>& rotations, int num_threads)
{
  if (pairs.empty())
    return {};
  const int B = checkedPairBandwidth(pairs);
  const int P = static_cast<int>(pairs.size());
  const int K = static_cast<int>(rotations.size());
  const EvaluationPoints points = evaluationPoints(rotations, B);
  const std::vector<double> log_factorials = logFactorials(2 * B + 1);
  const std::shared_ptr<const WignerStepTable> steps = wignerStepTable(B);
  // Per-order partial sums, reduced in a fixed order: identical for any thread count.
  const std::size_t PK = static_cast<std::size_t>(P) * K;
  std::vector<double> partial(static_cast<std::size_t>(B) * PK, 0.0);
  detail::parallelFor(B, 1, num_threads,
                      [&](std::ptrdiff_t first, std::ptrdiff_t last, int) {
                        for (int m = static_cast<int>(first); m < last; ++m)
                          evaluateOrder(m, pairs, points, *steps, log_factorials,
                                        &partial[static_cast<std::size_t>(m) * PK]);
                      });
  std::vector<std::vector<double>> value(P, std::vector<double>(K, 0.0));
  for (int m = 0; m < B; ++m)
    for (int q = 0; q < P; ++q)
      for (int k = 0; k < K; ++k)
        value[q][k] += partial[static_cast<std::size_t>(m) * PK +
                               static_cast<std::size_t>(q) * K + k];
  return value;
}

} // namespace pcl::phaser
