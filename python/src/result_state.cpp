/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * A Result's state as bytes, every field bit for bit, so that results pickled by
 * multiprocessing or dask.distributed equal the ones computed in the caller.
 */
#include "bindings.h"

#include <cstring>
#include <type_traits>

namespace pcl::phaser::python {

namespace {

constexpr std::uint32_t kStateVersion = 1;

/** Appends values to, or reads them back from, one byte string. */
class State {
public:
  explicit State(std::string bytes = {})
      : bytes_(std::move(bytes))
  {
  }
  const std::string& bytes() const { return bytes_; }

  template <typename T>
  std::enable_if_t<std::is_arithmetic_v<T>> put(T v)
  {
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <typename T>
  std::enable_if_t<std::is_arithmetic_v<T>> get(T& v)
  {
    if (read_ + sizeof(T) > bytes_.size())
      throw py::value_error("pcl_phaser.Result: truncated state");
    std::memcpy(&v, bytes_.data() + read_, sizeof(T));
    read_ += sizeof(T);
  }
  template <typename Derived>
  void put(const Eigen::MatrixBase<Derived>& m)
  {
    for (Eigen::Index i = 0; i < m.size(); ++i)
      put(m.derived().data()[i]);
  }
  template <typename Derived>
  void get(Eigen::MatrixBase<Derived>& m)
  {
    for (Eigen::Index i = 0; i < m.size(); ++i)
      get(m.derived().data()[i]);
  }
  void put(const std::string& s)
  {
    put(static_cast<std::uint64_t>(s.size()));
    bytes_ += s;
  }
  void get(std::string& s)
  {
    std::uint64_t n = 0;
    get(n);
    if (read_ + n > bytes_.size())
      throw py::value_error("pcl_phaser.Result: truncated state");
    s = bytes_.substr(read_, n);
    read_ += n;
  }
  /** A count of items that follow, each at least \a item_bytes long. */
  std::size_t count(std::size_t item_bytes)
  {
    std::uint64_t n = 0;
    get(n);
    if (n > (bytes_.size() - read_) / item_bytes)
      throw py::value_error("pcl_phaser.Result: truncated state");
    return n;
  }

private:
  std::string bytes_;
  std::size_t read_ = 0;
};

/** Visits every field of a Verification, a Hypothesis, StageTimes or the result, in
 *  one order for writing and reading. */
template <typename V, typename S>
void visit(V& v, S& s)
{
  s(v.inlier_fraction), s(v.score), s(v.free_space_violation),
      s(v.reverse_free_space_violation), s(v.constraint), s(v.rank);
}

template <typename S>
void visitTimes(StageTimes& t, S& s)
{
  s(t.target), s(t.sampling), s(t.sht), s(t.so3), s(t.refinement), s(t.translation),
      s(t.verification), s(t.orientation);
}

template <typename S>
void visitHypothesis(Hypothesis& h, S& s)
{
  s(h.transformation), s(h.rotation), s(h.translation), s(h.rotation_score),
      s(h.overlap), s(h.from_orientation);
  visit(h.verification, s);
}

template <typename S>
void visitScalars(AlignResult& a, S& s)
{
  PhaserResult& r = a.result;
  PhaserDiagnostics& d = r.diagnostics;
  s(r.error), s(r.transformation), s(r.converged), s(r.projection_center),
      s(r.chosen_hypothesis), s(r.lever_arm), s(r.translation_covariance),
      s(r.fit_covariance), s(r.covariance);
  s(d.rotation_score), s(d.translation_score), s(d.normalized_overlap),
      s(d.runner_up_rank), s(d.runner_up_error), s(d.verification_radius),
      s(d.verification_samples), s(d.verified), s(d.passes);
  visit(d.verification, s);
  visitTimes(d.times, s);
}

struct Writer {
  State& state;
  void operator()(ProjectionCenter c) { state.put(static_cast<int>(c)); }
  template <typename T>
  void operator()(const T& v)
  {
    state.put(v);
  }
};

struct Reader {
  State& state;
  void operator()(ProjectionCenter& c)
  {
    int v = 0;
    state.get(v);
    if (v < 0 || v > static_cast<int>(ProjectionCenter::Automatic))
      throw py::value_error("pcl_phaser.Result: bad state");
    c = static_cast<ProjectionCenter>(v);
  }
  template <typename T>
  void operator()(T& v)
  {
    state.get(v);
  }
};

} // namespace

py::bytes resultState(const AlignResult& r)
{
  AlignResult copy = r; // the visitors take mutable references
  State state;
  Writer write{state};
  state.put(kStateVersion);
  visitScalars(copy, write);
  PhaserDiagnostics& d = copy.result.diagnostics;
  state.put(static_cast<std::uint64_t>(d.hypotheses.size()));
  for (Hypothesis& h : d.hypotheses)
    visitHypothesis(h, write);
  state.put(static_cast<std::uint64_t>(d.rotation_samples.size()));
  for (std::size_t i = 0; i < d.rotation_samples.size(); ++i)
    write(d.rotation_samples[i]), write(d.rotation_weights[i]);
  return py::bytes(state.bytes());
}

AlignResult resultFromState(const py::bytes& bytes)
{
  State state{std::string(bytes)};
  Reader read{state};
  std::uint32_t version = 0;
  state.get(version);
  if (version != kStateVersion)
    throw py::value_error("pcl_phaser.Result: state of another version");
  AlignResult r;
  visitScalars(r, read);
  PhaserDiagnostics& d = r.result.diagnostics;
  d.hypotheses.resize(state.count(sizeof(double)));
  for (Hypothesis& h : d.hypotheses)
    visitHypothesis(h, read);
  const std::size_t samples = state.count(5 * sizeof(double));
  d.rotation_samples.resize(samples);
  d.rotation_weights.resize(samples);
  for (std::size_t i = 0; i < samples; ++i)
    read(d.rotation_samples[i]), read(d.rotation_weights[i]);
  return r;
}

} // namespace pcl::phaser::python
