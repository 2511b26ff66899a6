/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser.Parameters: PhaserParameters with every field an attribute. The numeric
 * fields come from kParameterRanges (a new row is a new attribute); every assignment is
 * checked by validateParameters() and a bad value raises ValueError with its reason.
 */
#include "bindings.h"

#include <pcl_phaser/point_channels.h>

#include <climits>
#include <sstream>
#include <vector>

namespace pcl::phaser::python {

namespace {

/** The fields bound by hand: neither int nor double. */
const char* const kOtherFields[] = {"normalized_refinement", "projection_center",
                                    "channels"};

std::string rangeText(const ParameterRange& r)
{
  std::ostringstream out;
  out << r.min << ".." << r.max;
  return out.str();
}

/** \a v as an int for row \a r. \throws type_error / value_error */
int toInteger(const ParameterRange& r, const py::handle& v)
{
  if (py::isinstance<py::bool_>(v) || !PyIndex_Check(v.ptr()))
    throw py::type_error(std::string(r.name) + " takes an int, not " +
                         std::string(py::str(py::type::of(v).attr("__name__"))));
  const auto i = py::reinterpret_steal<py::int_>(PyNumber_Index(v.ptr()));
  int overflow = 0;
  const long long x = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
  if (overflow || x < INT_MIN || x > INT_MAX)
    throw py::value_error(std::string(r.name) + " = " + std::string(py::str(v)) +
                          " is outside its range " + rangeText(r) + " (" + r.meaning +
                          ")");
  return static_cast<int>(x);
}

/** \a v as a double for row \a r. \throws type_error */
double toReal(const char* name, const py::handle& v)
{
  if (py::isinstance<py::bool_>(v) || py::isinstance<py::str>(v) ||
      !PyNumber_Check(v.ptr()) || PyComplex_Check(v.ptr()))
    throw py::type_error(std::string(name) + " takes a number, not " +
                         std::string(py::str(py::type::of(v).attr("__name__"))));
  const double x = PyFloat_AsDouble(v.ptr());
  if (PyErr_Occurred())
    throw py::error_already_set();
  return x;
}

ProjectionCenter toCenter(const py::handle& v)
{
  if (py::isinstance<ProjectionCenter>(v))
    return v.cast<ProjectionCenter>();
  if (py::isinstance<py::str>(v)) {
    const std::string s = v.cast<std::string>();
    if (s == "sensor" || s == "sensor_origin")
      return ProjectionCenter::SensorOrigin;
    if (s == "centroid")
      return ProjectionCenter::Centroid;
    if (s == "auto" || s == "automatic")
      return ProjectionCenter::Automatic;
    throw py::value_error("projection_center '" + s +
                          "' is none of 'sensor', 'centroid', 'auto'");
  }
  throw py::type_error("projection_center takes a pcl_phaser.ProjectionCenter or "
                       "'sensor' / 'centroid' / 'auto'");
}

std::uint32_t toChannels(const py::handle& v)
{
  if (py::isinstance<py::bool_>(v) || !PyIndex_Check(v.ptr()))
    throw py::type_error("channels takes an int of CHANNEL_* flags");
  const auto i = py::reinterpret_steal<py::int_>(PyNumber_Index(v.ptr()));
  int overflow = 0;
  const long long x = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
  if (overflow || x < 0 || x > 0xffffffffLL)
    throw py::value_error("channels must be in 0..0xffffffff (CHANNEL_* flags)");
  return static_cast<std::uint32_t>(x);
}

/** Sets the hand-bound field \a name of \a p; false when \a name is none of them. */
bool setOther(PhaserParameters& p, const std::string& name, const py::handle& v)
{
  if (name == "normalized_refinement") {
    if (!py::isinstance<py::bool_>(v))
      throw py::type_error("normalized_refinement takes a bool");
    p.normalized_refinement = v.cast<bool>();
  } else if (name == "projection_center") {
    p.projection_center = toCenter(v);
  } else if (name == "channels") {
    p.channels = toChannels(v);
  } else {
    return false;
  }
  return true;
}

/** Sets field \a name of \a p to \a v, unvalidated.
 *  \throws type_error (wrong type, unknown name), value_error (not an int) */
void assignField(PhaserParameters& p, const std::string& name, const py::handle& v)
{
  if (const ParameterRange* r = findParameterRange(name)) {
    r->set(p, r->integer ? toInteger(*r, v) : toReal(r->name, v));
  } else if (!setOther(p, name, v)) {
    throw py::type_error("Parameters has no field '" + name + "'");
  }
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
  assignField(changed, name, v);
  PhaserParameters checked = changed;
  // A region's center may be set before its radius; align() refuses a radius of 0.
  if (checked.region && checked.region->radius == 0.0)
    checked.region->radius = 1.0;
  validate(checked);
  p = changed;
}

py::object getField(const PhaserParameters& p, const std::string& name)
{
  if (const ParameterRange* r = findParameterRange(name))
    return r->integer ? py::object(py::int_(p.*(r->integer)))
                      : py::object(py::float_(r->value(p)));
  if (name == "normalized_refinement")
    return py::bool_(p.normalized_refinement);
  if (name == "projection_center")
    return py::cast(p.projection_center);
  if (name == "channels")
    return py::int_(p.channels);
  throw py::type_error("Parameters has no field '" + name + "'");
}

/** Every field: the rows of kParameterRanges, then the hand-bound ones. */
std::vector<std::string> fieldNames()
{
  std::vector<std::string> names;
  for (const ParameterRange& r : kParameterRanges)
    names.emplace_back(r.name);
  for (const char* name : kOtherFields)
    names.emplace_back(name);
  return names;
}

py::dict fieldsOf(const PhaserParameters& p)
{
  py::dict d;
  for (const std::string& name : fieldNames())
    d[py::str(name)] = getField(p, name);
  return d;
}

PhaserParameters fromKeywords(const py::dict& kwargs)
{
  PhaserParameters p; // validated as a whole: fields may depend on each other
  for (const auto& [key, value] : kwargs)
    assignField(p, py::str(key), value);
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
    rows.append(py::dict(py::arg("name") = r.name,
                         py::arg("type") = r.integer ? "int" : "float",
                         py::arg("min") = r.min, py::arg("max") = r.max,
                         py::arg("unit") = r.unit, py::arg("meaning") = r.meaning,
                         py::arg("default") = getField(defaults, r.name)));
  return rows;
}

void bindNumericFields(py::class_<PhaserParameters>& cls)
{
  for (const ParameterRange& r : kParameterRanges) {
    const std::string name = r.name;
    const std::string doc = std::string(r.meaning) + "; " +
                            (r.integer ? "int" : "float") + " in " + rangeText(r) +
                            (*r.unit ? std::string(" ") + r.unit : std::string());
    cls.def_property(
        r.name, [name](const PhaserParameters& p) { return getField(p, name); },
        [name](PhaserParameters& p, const py::handle& v) { setField(p, name, v); },
        doc.c_str());
  }
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
  py::enum_<ProjectionCenter>(m, "ProjectionCenter",
                              "Where the clouds are projected on the sphere.")
      .value("SensorOrigin", ProjectionCenter::SensorOrigin)
      .value("Centroid", ProjectionCenter::Centroid)
      .value("Automatic", ProjectionCenter::Automatic);
  m.attr("CHANNEL_RANGE") = static_cast<std::uint32_t>(CHANNEL_RANGE);
  m.attr("CHANNEL_INTENSITY") = static_cast<std::uint32_t>(CHANNEL_INTENSITY);
  py::class_<PhaserParameters> cls(
      m, "Parameters",
      "Every setting of one registration (PhaserParameters), with the C++ defaults.\n"
      "Parameters(bandwidth=32, num_threads=1, ...); a value outside its range\n"
      "raises ValueError with the engine's reason and keeps the previous one.");
  cls.def(py::init([](const py::kwargs& kwargs) { return fromKeywords(kwargs); }));
  bindNumericFields(cls);
  cls.def_property(
      "normalized_refinement",
      [](const PhaserParameters& p) { return p.normalized_refinement; },
      [](PhaserParameters& p, const py::handle& v) {
        setField(p, "normalized_refinement", v);
      },
      "about sensor origins, refine the rotation again on the normalized correlation");
  cls.def_property(
      "projection_center",
      [](const PhaserParameters& p) { return p.projection_center; },
      [](PhaserParameters& p, const py::handle& v) {
        setField(p, "projection_center", v);
      },
      "ProjectionCenter (or 'sensor' / 'centroid' / 'auto')");
  cls.def_property(
      "channels", [](const PhaserParameters& p) { return p.channels; },
      [](PhaserParameters& p, const py::handle& v) { setField(p, "channels", v); },
      "CHANNEL_* flags: without CHANNEL_INTENSITY a fourth column is ignored");
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
