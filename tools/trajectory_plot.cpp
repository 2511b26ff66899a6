/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "trajectory_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <zlib.h>

namespace pcl {
namespace phaser {
namespace graph {

namespace {

/** An RGB raster, row 0 at the top. */
struct Image {
  int size;
  std::vector<unsigned char> rgb;
  void dot(int x, int y, const std::array<unsigned char, 3>& c)
  {
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const int u = x + dx, v = y + dy;
        if (u >= 0 && v >= 0 && u < size && v < size)
          std::copy(c.begin(), c.end(), rgb.begin() + 3 * (v * size + u));
      }
  }
  void line(Eigen::Vector2d a, Eigen::Vector2d b, const std::array<unsigned char, 3>& c)
  {
    const int steps =
        std::max(1, static_cast<int>(std::ceil((b - a).cwiseAbs().maxCoeff())));
    for (int k = 0; k <= steps; ++k) {
      const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(k) / steps);
      dot(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())),
          c);
    }
  }
};

void putU32(std::string& out, std::uint32_t v)
{
  for (int shift = 24; shift >= 0; shift -= 8)
    out.push_back(static_cast<char>((v >> shift) & 0xff));
}

void chunk(std::string& out, const char* type, const std::string& data)
{
  putU32(out, static_cast<std::uint32_t>(data.size()));
  const std::string body = std::string(type, 4) + data;
  out += body;
  putU32(out, static_cast<std::uint32_t>(
                  crc32(0L, reinterpret_cast<const Bytef*>(body.data()),
                        static_cast<uInt>(body.size()))));
}

/** The PNG file of \a image (filter 0 on every row), or empty when zlib fails. */
std::string encodePng(const Image& image)
{
  std::string raw;
  for (int y = 0; y < image.size; ++y) {
    raw.push_back('\0');
    raw.append(reinterpret_cast<const char*>(image.rgb.data()) + 3 * y * image.size,
               static_cast<std::size_t>(3 * image.size));
  }
  uLongf packed_size = compressBound(static_cast<uLong>(raw.size()));
  std::string packed(packed_size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(packed.data()), &packed_size,
                reinterpret_cast<const Bytef*>(raw.data()),
                static_cast<uLong>(raw.size()), 9) != Z_OK)
    return {};
  packed.resize(packed_size);
  std::string header;
  putU32(header, static_cast<std::uint32_t>(image.size));
  putU32(header, static_cast<std::uint32_t>(image.size));
  header += std::string("\x08\x02\x00\x00\x00", 5); // 8-bit RGB, no interlace
  std::string png("\x89PNG\r\n\x1a\n", 8);
  chunk(png, "IHDR", header);
  chunk(png, "IDAT", packed);
  chunk(png, "IEND", "");
  return png;
}

} // namespace

std::string writeTopView(const std::string& path, const std::vector<Polyline>& lines,
                         int size)
{
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector2d hi = -lo;
  for (const Polyline& l : lines)
    for (const Eigen::Vector2d& p : l.points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  if (!(hi.x() >= lo.x()))
    return "nothing to draw";
  const double margin = 0.05 * size;
  const double scale = (size - 2.0 * margin) / std::max(1e-9, (hi - lo).maxCoeff());
  const Eigen::Vector2d center = 0.5 * (lo + hi);
  const auto pixel = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(0.5 * size + scale * (p.x() - center.x()),
                           0.5 * size - scale * (p.y() - center.y()));
  };
  Image image{
      size, std::vector<unsigned char>(static_cast<std::size_t>(3 * size * size), 255)};
  for (const Polyline& l : lines) {
    const std::size_t stride = l.connected ? 1 : 2;
    for (std::size_t k = 0; k + 1 < l.points.size(); k += stride)
      image.line(pixel(l.points[k]), pixel(l.points[k + 1]), l.color);
  }
  const std::string png = encodePng(image);
  std::ofstream out(path, std::ios::binary);
  if (png.empty() || !out.write(png.data(), static_cast<std::streamsize>(png.size())))
    return "cannot write '" + path + "'";
  return {};
}

} // namespace graph
} // namespace phaser
} // namespace pcl
