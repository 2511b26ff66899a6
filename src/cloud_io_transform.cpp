/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
// Rigid transforms as text: parseTransform, loadTransform, saveTransform.
#include "cloud_io_detail.h"

#include <pcl_phaser/cloud_io.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace pcl {
namespace phaser {

using namespace io_detail;

namespace {

/** Transform files larger than this are certainly not 16 numbers. */
constexpr std::uintmax_t kMaxTransformFileBytes = 1u << 20;

std::string formatNumber(double value)
{
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.3g", value);
  return (buffer);
}

/** Collect the numbers of text ('#' comments skipped), at most 16. */
bool parseNumbers(const std::string& text, std::vector<double>& values,
                  std::string* error)
{
  std::size_t line_start = 0;
  while (line_start <= text.size()) {
    std::size_t line_end = text.find('\n', line_start);
    if (line_end == std::string::npos)
      line_end = text.size();
    std::string line = text.substr(line_start, line_end - line_start);
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos)
      line.resize(hash);
    for (const std::string& token : splitWhitespace(line)) {
      const char* begin = token.data();
      const char* end = token.data() + token.size();
      if (begin != end && *begin == '+')
        ++begin;
      double v = 0.0;
      const auto result = std::from_chars(begin, end, v);
      if (result.ec != std::errc() || result.ptr != end)
        return (fail(error, "'" + excerpt(token) + "' is not a number"));
      if (!std::isfinite(v))
        return (fail(error, "non-finite value '" + excerpt(token) + "'"));
      values.push_back(v);
      if (values.size() > 16)
        return (
            fail(error, "more than 16 numbers (expected 12 for 3x4 or 16 for 4x4)"));
    }
    line_start = line_end + 1;
  }
  return (true);
}

} // namespace

bool parseTransform(const std::string& text, Eigen::Matrix4d& transform,
                    std::string* error, double tolerance)
{
  if (!std::isfinite(tolerance) || tolerance < 0.0)
    return (fail(error,
                 "tolerance must be finite and >= 0, got " + formatNumber(tolerance)));
  std::vector<double> values;
  if (!parseNumbers(text, values, error))
    return (false);
  if (values.size() != 12 && values.size() != 16)
    return (fail(error, "expected 12 (3x4) or 16 (4x4) numbers, found " +
                            std::to_string(values.size())));
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  for (std::size_t i = 0; i < values.size(); ++i)
    m(static_cast<Eigen::Index>(i / 4), static_cast<Eigen::Index>(i % 4)) = values[i];
  if (values.size() == 16) {
    const Eigen::RowVector4d last = m.row(3);
    if ((last - Eigen::RowVector4d(0.0, 0.0, 0.0, 1.0)).cwiseAbs().maxCoeff() >
        tolerance)
      return (fail(error, "last row is (" + formatNumber(last(0)) + " " +
                              formatNumber(last(1)) + " " + formatNumber(last(2)) +
                              " " + formatNumber(last(3)) + "), expected (0 0 0 1)"));
  }
  const Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
  const double deviation =
      (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(deviation <= tolerance))
    return (fail(error, "the rotation block is not orthonormal: max |R^T R - I| = " +
                            formatNumber(deviation) + " > tolerance " +
                            formatNumber(tolerance)));
  const double det = r.determinant();
  if (!(det > 0.0))
    return (fail(error, "the rotation block has determinant " + formatNumber(det) +
                            " (a reflection, not a rotation)"));
  transform = m;
  return (true);
}

bool loadTransform(const std::string& path, Eigen::Matrix4d& transform,
                   std::string* error, double tolerance)
{
  try {
    std::uintmax_t size = 0;
    if (!checkInputFile(path, size, error))
      return (false);
    if (size > kMaxTransformFileBytes)
      return (fail(error, quoted(path) + ": too large for a transform file (" +
                              std::to_string(size) + " bytes)"));
    std::string text;
    if (!readBytes(path, 0, static_cast<std::size_t>(size), text))
      return (fail(error, quoted(path) + ": read error"));
    std::string why;
    if (!parseTransform(text, transform, &why, tolerance))
      return (fail(error, quoted(path) + ": " + why));
    return (true);
  } catch (const std::exception& e) {
    return (fail(error, quoted(path) + ": read error: " + excerpt(e.what(), 200)));
  }
}

bool saveTransform(const std::string& path, const Eigen::Matrix4d& transform,
                   std::string* error)
{
  if (path.empty())
    return (fail(error, "empty file name"));
  std::string text;
  for (Eigen::Index row = 0; row < 4; ++row) {
    for (Eigen::Index col = 0; col < 4; ++col) {
      char buffer[64];
      const auto result =
          std::to_chars(buffer, buffer + sizeof(buffer), transform(row, col));
      if (result.ec != std::errc())
        return (fail(error, quoted(path) + ": cannot format a matrix entry"));
      if (col > 0)
        text += ' ';
      text.append(buffer, result.ptr);
    }
    text += '\n';
  }
  return (writeFile(path, text.data(), text.size(), false, error));
}

} // namespace phaser
} // namespace pcl
