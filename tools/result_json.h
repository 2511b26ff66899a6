// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file result_json.h
 * \brief JSON members of the tools' outputs, `pcl_phaser_align --json` and the records
 * of `pcl_phaser_batch` alike: a result's fields (visitResultFields, core/result.h) and the rest.
 */
#pragma once

#include <pcl_phaser/core/parameters.h>
#include <pcl_phaser/core/result.h>

#include <Eigen/Core>

#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>

namespace pcl {
namespace phaser {

/** \brief A JSON object whose members keep the order they are written in. */
using JsonObject = nlohmann::ordered_json;

/** \brief A visitor of visitResultFields() that sets a member of \a object per field:
 *  numbers, booleans and strings as they are (dump() writes non-finite numbers as
 * null), matrices as row-major nested arrays, groups as objects. */
struct JsonFields {
  JsonObject& object;
  template <class T, class = std::enable_if_t<std::is_arithmetic_v<T>>>
  void operator()(const char* name, T value)
  {
    object[name] = value;
  }
  void operator()(const char* name, const std::string& text) { object[name] = text; }
  template <class Derived>
  void operator()(const char* name, const Eigen::MatrixBase<Derived>& m)
  {
    JsonObject& rows = object[name] = JsonObject::array();
    for (Eigen::Index r = 0; r < m.rows(); ++r) {
      JsonObject& row = rows.emplace_back(JsonObject::array());
      for (Eigen::Index c = 0; c < m.cols(); ++c)
        row.push_back(m(r, c));
    }
  }
  template <class Visit>
  void operator()(const char* name, const FieldGroup<Visit>& group)
  {
    group.visit(JsonFields{object[name] = JsonObject::object()});
  }
};

/** \brief Every row of kParameterRanges of \a p as a JSON object: numbers and
 *  booleans as they are, an enum's and flags' values as the tools write them ("auto",
 *  "all"). */
inline JsonObject parametersJson(const PhaserParameters& p)
{
  JsonObject o = JsonObject::object();
  for (const ParameterRange& r : kParameterRanges) {
    const double v = r.value(p);
    if (r.type == ParameterType::Integer)
      o[r.name] = static_cast<long long>(v);
    else if (r.type == ParameterType::Real)
      o[r.name] = v;
    else if (r.type == ParameterType::Boolean)
      o[r.name] = v != 0.0;
    else
      o[r.name] = parameterText(r, v);
  }
  return o;
}

} // namespace phaser
} // namespace pcl
