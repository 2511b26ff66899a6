/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * A Result as a dict of every field (visitResultState(), the keys of the tools' JSON)
 * for to_dict() and pickle: floats and float64 arrays keep every bit, so that results
 * pickled by multiprocessing or dask.distributed equal the ones computed in the caller.
 */
#include "field_properties.h"

#include <type_traits>
#include <vector>

namespace pcl::phaser::python {

namespace {

/** \a h as a T. Fixed-size Eigen types go through a dynamic matrix: GCC warns of
 *  uninitialized storage in pybind11's fixed-size caster. */
template <typename T>
T load(const py::handle& h)
{
  if constexpr (std::is_base_of_v<Eigen::MatrixBase<T>, T>) {
    const auto m = h.cast<Eigen::MatrixXd>();
    if (m.rows() != T::RowsAtCompileTime || m.cols() != T::ColsAtCompileTime)
      throw py::value_error("a matrix of another shape");
    return m;
  } else if constexpr (std::is_same_v<T, std::vector<Eigen::Vector4d>>) {
    T out;
    for (const py::handle item : h.cast<py::list>())
      out.push_back(load<Eigen::Vector4d>(item));
    return out;
  } else
    return h.cast<T>();
}

/** Assigns each field from dict[name], as DictWriter wrote it. */
struct DictReader {
  py::dict dict;
  template <typename T>
  void operator()(const char* name, T& value)
  {
    value = load<T>(dict[name]);
  }
  template <typename Visit>
  void operator()(const char* name, const FieldGroup<Visit>& group)
  {
    group.visit(DictReader{dict[name]});
  }
  template <typename Items, typename Visit>
  void operator()(const char* name, const FieldList<Items, Visit>& list)
  {
    const py::list items = dict[name];
    list.items.resize(items.size());
    for (std::size_t i = 0; i < items.size(); ++i)
      list.visit(list.items[i], DictReader{items[i]});
  }
};

} // namespace

py::dict resultState(const PhaserResult& r)
{
  DictWriter writer;
  visitResultState(r, writer);
  return writer.dict;
}

PhaserResult resultFromState(const py::dict& state)
{
  PhaserResult r;
  try {
    visitResultState(r, DictReader{state});
  } catch (const std::exception& e) { // a field missing or of another type
    throw py::value_error(std::string("pcl_phaser.Result: bad state: ") + e.what());
  }
  const PhaserDiagnostics& d = r.diagnostics;
  if (d.rotation_weights.size() != d.rotation_samples.size())
    throw py::value_error("pcl_phaser.Result: bad state: rotation weights");
  return r;
}

} // namespace pcl::phaser::python
