/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "support/error.h"

#include <pcl_phaser/core/parameters.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <omp.h>
#include <sstream>

namespace pcl::phaser {

static_assert(kParameterRanges[0].max == kMaxBandwidth, "bandwidth range");

namespace {

/** \brief \a v with \a digits significant digits, as printf's %g writes it. */
std::string number(double v, int digits)
{
  char text[64];
  std::snprintf(text, sizeof(text), "%.*g", digits, v);
  return text;
}

/** \brief \a identifier ("SensorOrigin") in snake case ("sensor_origin"). */
std::string snakeCase(const char* identifier)
{
  std::string out;
  for (const char* c = identifier; *c; ++c) {
    const bool upper = *c >= 'A' && *c <= 'Z';
    if (upper && c != identifier && !(c[-1] >= 'A' && c[-1] <= 'Z') && c[-1] != '_')
      out += '_';
    out += upper ? static_cast<char>(*c - 'A' + 'a') : *c;
  }
  return out;
}

/** \brief The value of the name \a text of row \a r (with \a enumerators an
 *  enumerator in snake case too); false when it has none. */
bool valueOfName(const ParameterRange& r, const std::string& text, double& v,
                 bool enumerators)
{
  for (std::size_t k = 0; k < r.name_count; ++k)
    if (text == r.names[k].name ||
        (enumerators && text == snakeCase(r.names[k].identifier)))
      return v = r.names[k].value, true;
  return false;
}

/** \brief \a text as a number: an integer in \a base (0: C's prefixes) when \a base
 *  >= 0, else a real; false when it is not. */
bool parseNumber(const std::string& text, int base, double& v)
{
  char* end = nullptr;
  errno = 0;
  const double x = base >= 0
                       ? static_cast<double>(std::strtoll(text.c_str(), &end, base))
                       : std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || (base >= 0 && errno != 0))
    return false;
  return v = x, true;
}

/** \brief The name of value \a v of a Choice row \a r; null when it has none. */
const ParameterName* nameOf(const ParameterRange& r, double v)
{
  for (std::size_t k = 0; k < r.name_count; ++k)
    if (v == r.names[k].value)
      return &r.names[k];
  return nullptr;
}

/** \brief A Flags row's \a text: "all", names joined by ',', or a number. */
bool parseFlags(const ParameterRange& r, const std::string& text, double& v)
{
  if (text == "all")
    return v = r.max, true;
  if (parseNumber(text, 0, v))
    return true;
  std::uint32_t bits = 0;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t end = std::min(text.find(',', at), text.size());
    double bit = 0.0;
    if (!valueOfName(r, text.substr(at, end - at), bit, false))
      return false;
    bits |= static_cast<std::uint32_t>(bit);
    at = end + 1;
  }
  return v = bits, true;
}

/** \brief A Flags row's value \a bits: "all", its names joined by ',', or the number
 *  when a bit has no name. */
std::string flagsText(const ParameterRange& r, double v)
{
  if (v == r.max)
    return "all";
  std::uint32_t left = static_cast<std::uint32_t>(v);
  std::string out;
  for (std::size_t k = 0; k < r.name_count; ++k)
    if (left & r.names[k].value) {
      out += (out.empty() ? "" : ",") + std::string(r.names[k].name);
      left &= ~r.names[k].value;
    }
  return left || out.empty() ? number(v, 10) : out;
}

} // namespace

const ParameterRange* findParameterRange(const std::string& name)
{
  for (const ParameterRange& r : kParameterRanges)
    if (name == r.name)
      return &r;
  return nullptr;
}

std::string parameterText(const ParameterRange& r, double v, int digits)
{
  switch (r.type) {
  case ParameterType::Boolean:
    return v != 0.0 ? "true" : "false";
  case ParameterType::Choice:
    return nameOf(r, v) ? nameOf(r, v)->name : number(v, digits);
  case ParameterType::Flags:
    return flagsText(r, v);
  default:
    return number(v, digits);
  }
}

bool parseParameter(const ParameterRange& r, const std::string& text, double& v,
                    bool enumerators)
{
  double x = 0.0;
  bool ok = false;
  if (r.type == ParameterType::Boolean) {
    static const char* const spellings[][2] = {
        {"true", "false"}, {"on", "off"}, {"yes", "no"}, {"1", "0"}};
    for (const auto& s : spellings)
      if (text == s[0] || text == s[1])
        ok = true, x = text == s[0] ? 1.0 : 0.0;
  } else if (r.type == ParameterType::Choice)
    ok = valueOfName(r, text, x, enumerators);
  else if (r.type == ParameterType::Flags)
    ok = parseFlags(r, text, x);
  else
    ok = parseNumber(text, r.type == ParameterType::Integer ? 10 : -1, x);
  if (!ok || !(x >= r.min && x <= r.max) || !std::isfinite(x))
    return false;
  return v = x, true;
}

std::string parameterValues(const ParameterRange& r)
{
  if (r.type == ParameterType::Boolean)
    return "true, false";
  if (r.type != ParameterType::Choice && r.type != ParameterType::Flags)
    return number(r.min, 6) + ".." + number(r.max, 6);
  std::string out = r.type == ParameterType::Flags ? "all, or any of " : "";
  for (std::size_t k = 0; k < r.name_count; ++k)
    out += (k ? ", " : "") + std::string(r.names[k].name);
  return out;
}

std::string parameterDomain(const ParameterRange& r)
{
  switch (r.type) {
  case ParameterType::Integer:
    return "an integer in " + parameterValues(r);
  case ParameterType::Boolean:
    return "true or false (on/off, yes/no, 1/0)";
  case ParameterType::Choice:
    return "one of " + parameterValues(r);
  case ParameterType::Flags:
    return parameterValues(r) + " joined by ',', or a number in " + number(r.min, 6) +
           ".." + number(r.max, 10);
  default:
    return (!std::strcmp(r.unit, "deg") ? "degrees in "
            : !std::strcmp(r.unit, "m") ? "meters in "
                                        : "a number in ") +
           parameterValues(r);
  }
}

std::string validateParameters(const PhaserParameters& p)
{
  for (const ParameterRange& r : kParameterRanges) {
    const double v = r.value(p);
    const bool choice = r.type == ParameterType::Choice;
    if ((!choice && v >= r.min && v <= r.max && std::isfinite(v)) ||
        (choice && nameOf(r, v)) ||
        (!std::strcmp(r.name, "spatial_grid_size") && p.voxel_size > 0.0))
      continue;
    std::ostringstream out;
    out << r.name << " = " << v;
    if (choice)
      out << " is none of " << parameterValues(r);
    else
      out << " is outside its range " << r.min << ".." << r.max;
    out << " (" << r.meaning << ")";
    return out.str();
  }
  if (p.region && !(p.region->radius > 0.0))
    return "region_radius = 0 with a region: a position prior needs a radius > 0 m";
  return {};
}

int resolveThreadCount(int num_threads)
{
  return num_threads > 0 ? num_threads : std::clamp(omp_get_num_procs(), 1, 64);
}

} // namespace pcl::phaser
