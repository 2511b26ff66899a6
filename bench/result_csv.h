/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
/** \file result_csv.h
 * \brief The benchmarks' CSV columns of a pcl_phaser result: the fields of
 * visitResultFields() under the names `pcl_phaser_align --json` and the batch's records
 * use (a group's members as `stages_ms.target`, ...), empty for the other methods.
 */
#pragma once

#include <pcl_phaser/core/result.h>

#include <Eigen/Core>

#include <cstdio>
#include <ostream>
#include <string>
#include <type_traits>

namespace pcl::phaser {
namespace bench {

/** \brief A visitor of visitResultFields() that writes one CSV cell per field, each
 *  after a comma: the field's name (header), its value, or nothing (a method without a
 *  pcl_phaser result). Numbers as %.9g, booleans as 0 / 1, strings quoted; a matrix
 *  (covariance) is left out, the NEES columns summarize it. */
struct CsvFields {
  enum class Cell { Name, Value, Empty };
  std::ostream& out;
  Cell cell;
  std::string prefix; ///< a group's name and a period

  template <class T, class = std::enable_if_t<std::is_arithmetic_v<T>>>
  void operator()(const char* name, T value)
  {
    char text[32];
    std::snprintf(text, sizeof(text), "%.9g", static_cast<double>(value));
    write(name, text);
  }
  void operator()(const char* name, const std::string& text)
  {
    std::string quoted = "\"";
    for (const char c : text)
      quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    write(name, quoted + "\"");
  }
  template <class Derived>
  void operator()(const char*, const Eigen::MatrixBase<Derived>&)
  {
  }
  template <class Visit>
  void operator()(const char* name, const FieldGroup<Visit>& group)
  {
    group.visit(CsvFields{out, cell, prefix + name + "."});
  }

private:
  void write(const char* name, const std::string& value)
  {
    out << ','
        << (cell == Cell::Name    ? prefix + name
            : cell == Cell::Value ? value
                                  : "");
  }
};

/** \brief The result columns' names, each after a comma. */
inline void writeResultHeader(std::ostream& out)
{
  const PhaserResult none;
  visitResultFields(none, CsvFields{out, CsvFields::Cell::Name, ""});
}

/** \brief The result columns of \a result, each after a comma; empty cells without
 *  one. */
inline void writeResultCells(std::ostream& out, const PhaserResult* result)
{
  const PhaserResult none;
  visitResultFields(
      result ? *result : none,
      CsvFields{out, result ? CsvFields::Cell::Value : CsvFields::Cell::Empty, ""});
}

} // namespace bench
} // namespace pcl::phaser
