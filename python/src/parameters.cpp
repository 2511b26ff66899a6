/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser.Parameters: PhaserParameters with every field an attribute, made from the
 * rows of kParameterRanges (a new row is a new attribute and keyword): an int, a float,
 * a bool, an enum (its Python enum or a name) or flags (an int of CHANNEL_* bits).
 * Every assignment is checked by validateParameters() and a bad value raises ValueError
 * with its reason.
 */
#include "bindings.h"

#include <climits>
#include <map>
#include <vector>

namespace pcl::phaser::python {

namespace {

/** The Python enum of each Choice row by the row's name (bindChoice()). */
std::map<std::string, py::handle>& choiceTypes()
{
  static std::map<std::string, py::handle> types;
  return types;
}

std::string typeName(const py::handle& v)
{
  return py::str(py::type::of(v).attr("__name__"));
}

std::string outOfRange(const ParameterRange& r, const py::handle& v)
{
  return std::string(r.name) + " = " + std::string(py::str(v)) +
         " is outside its range " + parameterValues(r) + " (" + r.meaning + ")";
}

/** \a v as an integer for row \a r, within \a lo..\a hi. \throws type_error /
 *  value_error */
long long toInteger(const ParameterRange& r, const py::handle& v, long long lo,
                    long long hi)
{
  if (py::isinstance<py::bool_>(v) || !PyIndex_Check(v.ptr()))
    throw py::type_error(std::string(r.name) + " takes an int, not " + typeName(v));
  const auto i = py::reinterpret_steal<py::int_>(PyNumber_Index(v.ptr()));
  int overflow = 0;
  const long long x = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
  if (overflow || x < lo || x > hi)
    throw py::value_error(outOfRange(r, v));
  return x;
}

/** \a v as a double for row \a r. \throws type_error */
double toReal(const ParameterRange& r, const py::handle& v)
{
  if (py::isinstance<py::bool_>(v) || py::isinstance<py::str>(v) ||
      !PyNumber_Check(v.ptr()) || PyComplex_Check(v.ptr()))
    throw py::type_error(std::string(r.name) + " takes a number, not " + typeName(v));
  const double x = PyFloat_AsDouble(v.ptr());
  if (PyErr_Occurred())
    throw py::error_already_set();
  return x;
}

/** The names of Choice row \a r as Python writes them: 'sensor' / 'centroid' / ... */
std::string quotedNames(const ParameterRange& r, const char* separator)
{
  std::string out;
  for (std::size_t k = 0; k < r.name_count; ++k)
    out += (k ? separator : "") + ("'" + std::string(r.names[k].name) + "'");
  return out;
}

/** \a v, the Python enum of row \a r or one of its names, as its value.
 *  \throws type_error / value_error */
double toChoice(const ParameterRange& r, const py::handle& v)
{
  const auto type = choiceTypes().find(r.name);
  const bool bound = type != choiceTypes().end();
  if (bound && py::isinstance(v, type->second))
    return py::int_(py::reinterpret_borrow<py::object>(v)).cast<double>();
  if (!py::isinstance<py::str>(v))
    throw py::type_error(
        std::string(r.name) + " takes a pcl_phaser." +
        (bound ? std::string(py::str(type->second.attr("__name__"))) : "enum") +
        " or " + quotedNames(r, " / "));
  double x = 0.0;
  if (!parseParameter(r, v.cast<std::string>(), x, true))
    throw py::value_error(std::string(r.name) + " '" + v.cast<std::string>() +
                          "' is none of " + quotedNames(r, ", "));
  return x;
}

/** \a v as a value of row \a r. \throws type_error / value_error */
double toValue(const ParameterRange& r, const py::handle& v)
{
  switch (r.type) {
  case ParameterType::Integer:
    return static_cast<double>(toInteger(r, v, INT_MIN, INT_MAX));
  case ParameterType::Boolean:
    if (!py::isinstance<py::bool_>(v))
      throw py::type_error(std::string(r.name) + " takes a bool, not " + typeName(v));
    return v.cast<bool>() ? 1.0 : 0.0;
  case ParameterType::Choice:
    return toChoice(r, v);
  case ParameterType::Flags:
    return static_cast<double>(
        toInteger(r, v, static_cast<long long>(r.min), static_cast<long long>(r.max)));
  default:
    return toReal(r, v);
  }
}

/** The row of field \a name. \throws type_error when there is none */
const ParameterRange& rowOf(const std::string& name)
{
  if (const ParameterRange* r = findParameterRange(name))
    return *r;
  throw py::type_error("Parameters has no field '" + name + "'");
}

void validate(const PhaserParameters& p)
{
  const std::string problem = validateParameters(p);
  if (!problem.empty())
    throw py::value_error(problem);
}

/** Sets field \a name of \a p to \a v when the whole set then validates.
 *  \throws type_error (wrong type, unknown name), value_error (the engine's reason) */
void setField(PhaserParameters& p, const std::string& name, const py::handle& v)
{
  PhaserParameters changed = p;
  const ParameterRange& r = rowOf(name);
  r.set(changed, toValue(r, v));
  PhaserParameters checked = changed;
  // A region's center may be set before its radius; align() refuses a radius of 0.
  if (checked.region && checked.region->radius == 0.0)
    checked.region->radius = 1.0;
  validate(checked);
  p = changed;
}

py::object getField(const PhaserParameters& p, const ParameterRange& r)
{
  const double v = r.value(p);
  const auto type = choiceTypes().find(r.name);
  switch (r.type) {
  case ParameterType::Integer:
  case ParameterType::Flags:
    return py::int_(static_cast<long long>(v));
  case ParameterType::Boolean:
    return py::bool_(v != 0.0);
  case ParameterType::Choice:
    if (type != choiceTypes().end())
      return type->second(static_cast<long long>(v));
    return py::str(parameterText(r, v));
  default:
    return py::float_(v);
  }
}

/** Every field: the names of the rows of kParameterRanges. */
std::vector<std::string> fieldNames()
{
  std::vector<std::string> names;
  for (const ParameterRange& r : kParameterRanges)
    names.emplace_back(r.name);
  return names;
}

py::dict fieldsOf(const PhaserParameters& p)
{
  py::dict d;
  for (const ParameterRange& r : kParameterRanges)
    d[py::str(r.name)] = getField(p, r);
  return d;
}

PhaserParameters fromKeywords(const py::dict& kwargs)
{
  PhaserParameters p; // validated as a whole: fields may depend on each other
  for (const auto& [key, value] : kwargs) {
    const ParameterRange& r = rowOf(py::str(key));
    r.set(p, toValue(r, value));
  }
  validate(p);
  return p;
}

std::string reprOf(const PhaserParameters& p)
{
  const py::dict mine = fieldsOf(p), defaults = fieldsOf(PhaserParameters());
  std::string out = "Parameters(";
  bool first = true;
  for (const auto& [key, value] : mine) {
    if (value.equal(defaults[key]))
      continue;
    out += (first ? "" : ", ") + std::string(py::str(key)) + "=" +
           std::string(py::repr(value));
    first = false;
  }
  return out + ")";
}

/** The numeric rows as dicts: name, type, min, max, unit, meaning, default. */
py::list rangeTable()
{
  py::list rows;
  const PhaserParameters defaults;
  for (const ParameterRange& r : kParameterRanges)
    if (r.type == ParameterType::Integer || r.type == ParameterType::Real)
      rows.append(py::dict(
          py::arg("name") = r.name,
          py::arg("type") = r.type == ParameterType::Integer ? "int" : "float",
          py::arg("min") = r.min, py::arg("max") = r.max, py::arg("unit") = r.unit,
          py::arg("meaning") = r.meaning, py::arg("default") = getField(defaults, r)));
  return rows;
}

/** What row \a r takes, for its docstring: "int in 2..256", "bool", ... */
std::string typeDoc(const ParameterRange& r)
{
  const auto type = choiceTypes().find(r.name);
  switch (r.type) {
  case ParameterType::Integer:
  case ParameterType::Real:
    return (r.type == ParameterType::Integer ? "int in " : "float in ") +
           parameterValues(r) + (*r.unit ? std::string(" ") + r.unit : std::string());
  case ParameterType::Boolean:
    return "bool";
  case ParameterType::Choice:
    return (type != choiceTypes().end()
                ? std::string(py::str(type->second.attr("__name__"))) + " or "
                : std::string()) +
           quotedNames(r, " / ");
  default:
    return "int of CHANNEL_* flags";
  }
}

void bindFields(py::class_<PhaserParameters>& cls)
{
  for (const ParameterRange& r : kParameterRanges) {
    const std::string name = r.name;
    const std::string doc = std::string(r.meaning) + "; " + typeDoc(r);
    cls.def_property(
        r.name, [&r](const PhaserParameters& p) { return getField(p, r); },
        [name](PhaserParameters& p, const py::handle& v) { setField(p, name, v); },
        doc.c_str());
  }
}

/** The Python enum \a type_name of Choice row \a row, its values named by the row's
 *  enumerators. */
template <class Enum>
void bindChoice(py::module_& m, const char* type_name, const char* doc, const char* row)
{
  py::enum_<Enum> type(m, type_name, doc);
  const ParameterRange& r = *findParameterRange(row);
  for (std::size_t k = 0; k < r.name_count; ++k)
    type.value(r.names[k].identifier, static_cast<Enum>(r.names[k].value));
  choiceTypes()[row] = type;
}

} // namespace

PhaserParameters parametersFrom(const py::handle& params)
{
  if (params.is_none())
    return {};
  if (py::isinstance<py::dict>(params))
    return fromKeywords(py::reinterpret_borrow<py::dict>(params));
  if (py::isinstance<PhaserParameters>(params))
    return params.cast<PhaserParameters>();
  throw py::type_error("params must be a pcl_phaser.Parameters, a dict or None");
}

bool usesIntensity(const PhaserParameters& params)
{
  return (params.channels & CHANNEL_INTENSITY) != 0;
}

void bindParameters(py::module_& m)
{
  bindChoice<ProjectionCenter>(m, "ProjectionCenter",
                               "Where the clouds are projected on the sphere.",
                               "projection_center");
  for (const ParameterRange& r : kParameterRanges)
    for (std::size_t k = 0; r.type == ParameterType::Flags && k < r.name_count; ++k)
      m.attr(r.names[k].identifier) = r.names[k].value; // CHANNEL_RANGE, ...
  py::class_<PhaserParameters> cls(
      m, "Parameters",
      "Every setting of one registration (PhaserParameters), with the C++ defaults.\n"
      "Parameters(bandwidth=32, num_threads=1, ...); a value outside its range\n"
      "raises ValueError with the engine's reason and keeps the previous one.");
  cls.def(py::init([](const py::kwargs& kwargs) { return fromKeywords(kwargs); }));
  bindFields(cls);
  cls.def_static("fields", &fieldNames, "The names of every field.");
  cls.def("to_dict", &fieldsOf, "Every field as a dict.");
  cls.def("__repr__", &reprOf);
  cls.def("__eq__", [](const PhaserParameters& a, const PhaserParameters& b) {
    return fieldsOf(a).equal(fieldsOf(b));
  });
  cls.def(py::pickle([](const PhaserParameters& p) { return fieldsOf(p); },
                     [](const py::dict& d) { return fromKeywords(d); }));
  m.attr("PARAMETER_RANGES") = rangeTable();
}

} // namespace pcl::phaser::python
