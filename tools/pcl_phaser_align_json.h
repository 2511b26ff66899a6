// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file pcl_phaser_align_json.h
 * \brief The few JSON writers `pcl_phaser_align --json` needs (numbers, booleans,
 * strings, matrices, objects, the result's fields, a registration stage), hand-written
 * so that the tool needs no JSON library.
 */
#pragma once

#include "pcl_phaser_align_steps.h"

#include <pcl_phaser/core/result_fields.h>

#include <Eigen/Core>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace pcl {
namespace phaser {
namespace json {

/** \brief A number with 9 significant digits ("%.9g"); null when it is not finite,
 * since JSON has no NaN or infinity. */
inline std::string number(double value)
{
  if (!std::isfinite(value))
    return ("null");
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.9g", value);
  return (buffer);
}

/** \brief true or false. */
inline std::string boolean(bool value)
{
  return (value ? "true" : "false");
}

/** \brief A quoted string with ", \ and control characters escaped. */
inline std::string quote(const std::string& text)
{
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (static_cast<unsigned char>(c) < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof(buffer), "\\u%04x", static_cast<unsigned>(c));
      out += buffer;
    } else
      out += c;
  }
  return (out + "\"");
}

/** \brief A matrix as row-major nested arrays: [[r0], [r1], ...]. */
template <class Derived>
std::string matrix(const Eigen::MatrixBase<Derived>& m)
{
  std::string out = "[";
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    out += r ? ", [" : "[";
    for (Eigen::Index c = 0; c < m.cols(); ++c)
      out += (c ? ", " : "") + number(m(r, c));
    out += "]";
  }
  return (out + "]");
}

/** \brief An object whose members keep their insertion order. Values are raw JSON
 * text, built with the functions above or another Object's str(). */
class Object {
public:
  /** \brief Append a member. \param[in] key the name \param[in] raw_value JSON text */
  Object& add(const std::string& key, const std::string& raw_value)
  {
    members_.emplace_back(key, raw_value);
    return (*this);
  }

  /** \brief The object on one line. */
  std::string str() const
  {
    std::string out = "{";
    for (std::size_t i = 0; i < members_.size(); ++i)
      out += (i ? ", " : "") + quote(members_[i].first) + ": " + members_[i].second;
    return (out + "}");
  }

private:
  std::vector<std::pair<std::string, std::string>> members_;
};

/** \brief A visitor of visitResultFields() (result_fields.h) adding each field to
 * \a object; a group becomes a nested object. */
struct FieldWriter {
  Object& object;
  void operator()(const char* name, double v) { object.add(name, number(v)); }
  void operator()(const char* name, int v) { object.add(name, std::to_string(v)); }
  void operator()(const char* name, bool v) { object.add(name, boolean(v)); }
  template <class Derived>
  void operator()(const char* name, const Eigen::MatrixBase<Derived>& m)
  {
    object.add(name, matrix(m));
  }
  template <class Visit>
  void operator()(const char* name, const FieldGroup<Visit>& group)
  {
    Object members;
    group.visit(FieldWriter{members});
    object.add(name, members.str());
  }
};

/** \brief A stage as {"transformation", "converged", "time_ms"} plus "rre_deg" and
 * "rte_m" when its errors are known. */
inline Object stage(const pcl::phaser::align_tool::Stage& s)
{
  Object o;
  o.add("transformation", matrix(s.transform))
      .add("converged", boolean(s.converged))
      .add("time_ms", number(s.time_ms));
  if (std::isfinite(s.rre_deg))
    o.add("rre_deg", number(s.rre_deg)).add("rte_m", number(s.rte_m));
  return (o);
}

} // namespace json
} // namespace phaser
} // namespace pcl
