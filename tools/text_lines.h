// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file text_lines.h
 * \brief The line reader of the tools' text formats (pair and scan lists, poses, g2o
 * graphs and their merge): `#` starts a comment, blank lines are skipped, and a reason
 * names the file and the line.
 */
#pragma once

#include <cerrno>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace pcl {
namespace phaser {

/** \brief \a line without its comment, split at white space. */
inline std::vector<std::string> lineFields(const std::string& line)
{
  std::istringstream in(line.substr(0, line.find('#')));
  std::vector<std::string> out;
  for (std::string t; in >> t;)
    out.push_back(t);
  return out;
}

/** \brief Call \a take with each line of \a path that holds more than a comment (the
 *  text before `#`) and its number (from 1); stop at the first reason it returns,
 *  prefixed with "'PATH' line N: ".
 *  \return empty when every line was taken, else the reason */
inline std::string
forEachLine(const std::string& path,
            const std::function<std::string(const std::string&, int)>& take)
{
  std::ifstream in(path);
  if (!in)
    return "cannot read '" + path + "': " + std::strerror(errno);
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    const std::string text = line.substr(0, line.find('#'));
    if (++number, text.find_first_not_of(" \t\r\v\f") == std::string::npos)
      continue;
    if (std::string reason = take(text, number); !reason.empty())
      return "'" + path + "' line " + std::to_string(number) + ": " + reason;
  }
  return in.bad() ? "cannot read '" + path + "': read error" : std::string();
}

} // namespace phaser
} // namespace pcl
