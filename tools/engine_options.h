/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
/** \file engine_options.h
 * \brief The engine settings of pcl_phaser_align and pcl_phaser_batch: one option per
 * row of pcl::phaser::kParameterRanges (`--<name with - for _>`, the documented ones
 * also under a short alias: -b, --grid, --threads, --center, --max-tilt), plus
 * --region X,Y,Z,R. Both tools parse, check (range, names) and document them from this
 * table, and read their command lines with collectArguments().
 */
#pragma once

#include <pcl_phaser/core/parameters.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace pcl {
namespace phaser {

/** \brief One engine option: a row of kParameterRanges, or --region. */
struct EngineOption {
  std::string flag;            ///< the long name, e.g. --bandwidth
  const char* alias;           ///< a short name, e.g. -b; null when none
  const char* value_name;      ///< the value in the help, e.g. B
  const ParameterRange* range; ///< the row; null for --region
};

/** \brief The option of row \a r: its name with - for _, alias and help value. */
inline EngineOption engineOptionOf(const ParameterRange& r)
{
  // The help value of each ParameterType, in its order.
  static const char* const value_names[] = {"N", "X", "BOOL", "NAME", "LIST"};
  EngineOption o{"--" + std::string(r.name), nullptr,
                 value_names[static_cast<int>(r.type)], &r};
  for (char& c : o.flag)
    c = c == '_' ? '-' : c;
  if (!std::strcmp(r.unit, "m"))
    o.value_name = "M";
  // The short names and help values of the documented settings.
  static const char* const aliases[][3] = {{"bandwidth", "-b", "B"},
                                           {"spatial_grid_size", "--grid", "N"},
                                           {"passes", nullptr, "K"},
                                           {"num_threads", "--threads", "T"},
                                           {"projection_center", "--center", "MODE"},
                                           {"max_tilt_deg", "--max-tilt", "DEG"}};
  for (const auto& a : aliases)
    if (!std::strcmp(a[0], r.name))
      o.alias = a[1], o.value_name = a[2];
  return o;
}

/** \brief Every engine option: --region, then kParameterRanges' rows. */
inline const std::vector<EngineOption>& engineOptions()
{
  static const std::vector<EngineOption> options = [] {
    std::vector<EngineOption> out = {{"--region", nullptr, "X,Y,Z,R", nullptr}};
    for (const ParameterRange& r : kParameterRanges)
      out.push_back(engineOptionOf(r));
    return out;
  }();
  return options;
}

/** \brief The index in engineOptions() of \a flag (a name or alias); -1: none. */
inline int findEngineOption(const std::string& flag)
{
  const std::vector<EngineOption>& options = engineOptions();
  for (std::size_t k = 0; k < options.size(); ++k)
    if (flag == options[k].flag || (options[k].alias && flag == options[k].alias))
      return static_cast<int>(k);
  return -1;
}

/** \brief The name of a projection center, as --center takes it. */
inline const char* centerName(ProjectionCenter center)
{
  for (const ParameterName& n : kProjectionCenterNames)
    if (n.value == static_cast<std::uint32_t>(center))
      return n.name;
  return "?";
}

/** \brief \a text as an integer in \a lo..\a hi into \a v; false when it is not. */
inline bool parseInteger(const std::string& text, long lo, long hi, long& v)
{
  char* end = nullptr;
  errno = 0;
  v = std::strtol(text.c_str(), &end, 10);
  return !text.empty() && *end == '\0' && errno == 0 && v >= lo && v <= hi;
}

/** \brief \a text as a finite number into \a v; false when it is not all one (empty,
 *  trailing characters, infinite or NaN). Leaves errno as std::strtod set it. */
inline bool parseNumber(const std::string& text, double& v)
{
  char* end = nullptr;
  v = std::strtod(text.c_str(), &end);
  return !text.empty() && *end == '\0' && std::isfinite(v);
}

/** \brief \a text as two numbers "A,B", each as parseNumber() takes it, into \a a
 *  and \a b; false when it is not. */
inline bool parseNumberPair(const std::string& text, double& a, double& b)
{
  const std::size_t comma = text.find(',');
  return comma != std::string::npos && parseNumber(text.substr(0, comma), a) &&
         parseNumber(text.substr(comma + 1), b);
}

/** \brief Sets row \a r of \a p from \a text given as \a flag; empty, or the message
 *  naming the option, what it takes and its meaning. */
inline std::string setFromText(const ParameterRange& r, const std::string& flag,
                               const std::string& text, PhaserParameters& p)
{
  double v = 0.0;
  if (parseParameter(r, text, v))
    return r.set(p, v), std::string();
  const std::string expected = parameterDomain(r) + " (" + r.meaning + ")";
  if (r.type == ParameterType::Integer)
    return "Invalid value '" + text + "' for " + flag + ": expected " + expected;
  return "Invalid " + flag + " '" + text + "': expected " + expected;
}

/** \brief --region X,Y,Z,R (meters, the target's frame) into \a p as the rows
 *  region_x, _y, _z and _radius take them, R > 0. \return false when it is not */
inline bool setRegion(const std::string& text, PhaserParameters& p)
{
  PhaserParameters q;
  q.region = Region{};
  std::size_t at = 0;
  for (const char* row : {"region_x", "region_y", "region_z", "region_radius"}) {
    const std::size_t end =
        std::min(text.find(',', std::min(at, text.size())), text.size());
    if (at > end ||
        !setFromText(*findParameterRange(row), "", text.substr(at, end - at), q)
             .empty())
      return false;
    at = end + 1;
  }
  if (at != text.size() + 1 || !q.region) // more numbers, or R = 0
    return false;
  p.region = q.region;
  return true;
}

/** \brief Sets \a p from engine option \a o given as \a flag with \a text; empty, or
 *  the message naming the option and what it takes. */
inline std::string setEngineOption(const EngineOption& o, const std::string& flag,
                                   const std::string& text, PhaserParameters& p)
{
  if (o.range)
    return setFromText(*o.range, flag, text, p);
  if (setRegion(text, p))
    return {};
  char max[32];
  std::snprintf(max, sizeof(max), "%g", findParameterRange("region_radius")->max);
  return "Invalid --region '" + text +
         "': expected X,Y,Z,R in meters in the target's frame, coordinates within "
         "1e6 m and 0 < R <= " +
         max;
}

/** \brief The engine options of one command line by their index in engineOptions():
 *  the flag as given and its value (collectArguments()). */
using EngineArguments = std::map<int, std::pair<std::string, std::string>>;

/** \brief A command line: the tool's options by name (a switch maps to ""), the
 *  engine's, and the other arguments (files). */
struct CommandLine : std::map<std::string, std::string> {
  EngineArguments engine;
  std::vector<std::string> files;
  /** \brief The value of option \a name into \a value; false when not given. */
  bool value(const std::string& name, std::string& value) const
  {
    const auto it = find(name);
    return it != end() ? (value = it->second, true) : false;
  }
};

/** \brief Collects \a argv into \a line: the engine options (unless \a engine is
 *  false: a tool that runs no align), the tool's \a switches and \a valued options,
 *  each once, and the files. \return empty, or the problem */
inline std::string collectArguments(int argc, char** argv,
                                    const std::set<std::string>& switches,
                                    const std::set<std::string>& valued,
                                    CommandLine& line, bool engine = true)
{
  std::string error;
  for (int i = 1; i < argc && error.empty(); ++i) {
    const std::string name = argv[i];
    const int k = engine ? findEngineOption(name) : -1;
    const bool has_value = k >= 0 || valued.count(name) > 0;
    if (!has_value && !switches.count(name)) {
      if (name.size() > 1 && name[0] == '-')
        error = "Unknown argument '" + name + "'";
      line.files.push_back(name);
    } else if (has_value && i + 1 >= argc)
      error = "Option " + name + " needs a value";
    else if (k >= 0 ? line.engine.count(k) > 0 : line.count(name) > 0)
      error = "Option " + name + " is given twice";
    else if (k >= 0)
      line.engine[k] = {name, argv[++i]};
    else
      line[name] = has_value ? argv[++i] : "";
  }
  return error;
}

/** \brief Sets \a p from \a args in table order (--region before its fields), then
 *  checks the whole with validateParameters(). \return empty, or the first problem */
inline std::string setEngineOptions(const EngineArguments& args, PhaserParameters& p)
{
  for (const auto& [k, given] : args) {
    const std::string error =
        setEngineOption(engineOptions()[k], given.first, given.second, p);
    if (!error.empty())
      return error;
  }
  const std::string problem = validateParameters(p);
  return problem.empty() ? problem : "Invalid engine settings: " + problem;
}

/** \brief The help lines of every engine option with the defaults \a d, e.g.
 *  "    -b B, --bandwidth   = spherical bandwidth ...; 2..256 (default: 64)". */
inline std::string engineOptionsHelp(const PhaserParameters& d)
{
  std::string out;
  char line[512];
  for (const EngineOption& o : engineOptions()) {
    const std::string name =
        o.alias ? std::string(o.alias) + " " + o.value_name + ", " + o.flag
                : o.flag + " " + o.value_name;
    std::string text;
    if (o.range) {
      const ParameterRange& r = *o.range;
      text = r.meaning + std::string("; ") + parameterValues(r) + (*r.unit ? " " : "") +
             r.unit + " (default: " + parameterText(r, r.value(d)) + ")";
    } else
      text =
          "position prior: the source's sensor within R m of (X, Y, Z), target frame "
          "(sets the region_* rows)";
    // A long name on a line of its own, the text below it.
    const char* gap = name.size() > 19 ? "\n                       " : "";
    std::snprintf(line, sizeof(line), "    %-19s%s = %s\n", name.c_str(), gap,
                  text.c_str());
    out += line;
  }
  return out;
}

} // namespace phaser
} // namespace pcl
