/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "io_detail.h"
#include "transform_file.h"

#include <Eigen/LU>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

namespace pcl {
namespace phaser {

bool parseTransform(const std::string& text, Eigen::Matrix4d& transform,
                    std::string* error, double tolerance)
{
  using detail::fail;
  if (!std::isfinite(tolerance) || tolerance < 0.0)
    return (fail(error, "tolerance must be finite and >= 0"));
  std::vector<double> values;
  std::istringstream lines(text);
  for (std::string line, token; std::getline(lines, line);)
    for (std::istringstream tokens(line.substr(0, line.find('#'))); tokens >> token;) {
      const char* end = token.data() + token.size();
      double v = 0.0;
      const auto r = std::from_chars(token.data() + (token[0] == '+'), end, v);
      const bool number = r.ec == std::errc() && r.ptr == end;
      if (!number || !std::isfinite(v))
        return (fail(error, "'" + detail::printable(token, 40) +
                                (number ? "' is non-finite" : "' is not a number")));
      values.push_back(v);
    }
  if (values.size() != 12 && values.size() != 16)
    return (fail(error, "expected 12 (3x4) or 16 (4x4) numbers, found " +
                            std::to_string(values.size())));
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  for (std::size_t i = 0; i < values.size(); ++i)
    m(static_cast<Eigen::Index>(i / 4), static_cast<Eigen::Index>(i % 4)) = values[i];
  if (!((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() <= tolerance))
    return (fail(error, "the last row is not 0 0 0 1"));
  const Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
  const double deviation =
      (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  char why[160];
  std::snprintf(why, sizeof(why),
                "the rotation block is not orthonormal: max |R^T R - I| = %.3g > %.3g",
                deviation, tolerance);
  if (!(deviation <= tolerance))
    return (fail(error, why));
  std::snprintf(
      why, sizeof(why),
      "the rotation block has determinant %.3g (a reflection, not a rotation)",
      r.determinant());
  if (!(r.determinant() > 0.0))
    return (fail(error, why));
  transform = m;
  return (true);
}

bool loadTransform(const std::string& path, Eigen::Matrix4d& transform,
                   std::string* error, double tolerance)
{
  using namespace detail;
  std::uintmax_t size = 0;
  if (!checkInputFile(path, size, error))
    return (false);
  if (size > (1u << 20))
    return (fail(error, quoted(path) + ": too large for a transform file"));
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  std::string why;
  return (parseTransform(text, transform, &why, tolerance) ||
          fail(error, quoted(path) + ": " + why));
}

} // namespace phaser
} // namespace pcl
