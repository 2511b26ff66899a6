/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The result's field lists (core/result.h) as Python: a dict of the fields (to_dict(),
 * pickle) and read-only attributes named as the fields, so that a field listed there is
 * an attribute of its Python class without a line here.
 */
#pragma once

#include "bindings.h"

#include <pcl_phaser/core/result.h>

#include <cstring>
#include <vector>

namespace pcl::phaser::python {

/** \brief Sets dict[name] to each field it visits: a group as a dict, a list as a list
 *  of dicts. */
struct DictWriter {
  py::dict dict;
  template <typename T>
  void operator()(const char* name, const T& value)
  {
    dict[name] = py::cast(value, py::return_value_policy::copy);
  }
  template <typename Visit>
  void operator()(const char* name, const FieldGroup<Visit>& group)
  {
    DictWriter members;
    group.visit(members);
    dict[name] = members.dict;
  }
  template <typename Items, typename Visit>
  void operator()(const char* name, const FieldList<Items, Visit>& list)
  {
    py::list out;
    for (const auto& item : list.items) {
      DictWriter fields;
      list.visit(item, fields);
      out.append(fields.dict);
    }
    dict[name] = out;
  }
};

/** \brief Copies the field named \a name into \a out as a Python object: a group as a
 *  dict, a list as a list of its bound items (Hypothesis objects). */
struct FieldFinder {
  const char* name;
  py::object& out;
  template <typename T>
  void operator()(const char* field, const T& value)
  {
    if (std::strcmp(field, name) == 0)
      out = py::cast(value, py::return_value_policy::copy);
  }
  template <typename Visit>
  void operator()(const char* field, const FieldGroup<Visit>& group)
  {
    if (std::strcmp(field, name) != 0)
      return;
    DictWriter members;
    group.visit(members);
    out = members.dict;
  }
  template <typename Items, typename Visit>
  void operator()(const char* field, const FieldList<Items, Visit>& list)
  {
    if (std::strcmp(field, name) == 0)
      out = py::cast(list.items, py::return_value_policy::copy);
  }
};

/** \brief A read-only attribute of \a cls per field that visit(object, visitor) visits,
 *  named as the field (the names are string literals); its value is a copy. */
template <typename T, typename Visit>
void bindFieldProperties(py::class_<T>& cls, Visit visit)
{
  std::vector<const char*> names;
  const T probe{};
  visit(probe, [&names](const char* name, const auto&) { names.push_back(name); });
  for (const char* name : names)
    cls.def_property_readonly(name, [name, visit](const T& object) {
      py::object out;
      visit(object, FieldFinder{name, out});
      return out;
    });
}

} // namespace pcl::phaser::python
