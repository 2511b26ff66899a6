/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
// PLY: the walk over a body up to its range_grid element, checking vertex indices.
#include "cloud_io_detail.h"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <istream>
#include <string>
#include <vector>

namespace pcl {
namespace phaser {
namespace io_detail {
namespace {

/** Largest value of a PLY integer type. */
std::uint64_t plyTypeMax(const std::string& type)
{
  if (type == "char" || type == "int8")
    return (127);
  if (type == "uchar" || type == "uint8")
    return (255);
  if (type == "short" || type == "int16")
    return (32767);
  if (type == "ushort" || type == "uint16")
    return (65535);
  if (type == "int" || type == "int32")
    return (2147483647);
  return (4294967295u);
}

/** Read one binary PLY integer of the given type (1, 2 or 4 bytes, signed or not). */
bool readPlyInteger(std::istream& in, const std::string& type, bool big_endian,
                    std::int64_t& value)
{
  const std::uint64_t size = plyTypeSize(type);
  unsigned char bytes[4] = {0, 0, 0, 0};
  if (size == 0 || size > 4 || !in.read(reinterpret_cast<char*>(bytes), size))
    return (false);
  std::uint32_t u = 0;
  for (std::uint64_t i = 0; i < size; ++i) {
    const std::uint64_t k = big_endian ? i : size - 1 - i; // most significant first
    u = (u << 8) | bytes[k];
  }
  const bool is_signed = type == "char" || type == "int8" || type == "short" ||
                         type == "int16" || type == "int" || type == "int32";
  if (is_signed && size < 4 && (u >> (8 * size - 1)) != 0)
    value = static_cast<std::int64_t>(u) - (std::int64_t{1} << (8 * size));
  else if (is_signed && size == 4)
    value = static_cast<std::int32_t>(u);
  else
    value = u;
  return (true);
}

/** The body walker: one record at a time, ascii or binary. */
class RangeGridWalker {
public:
  RangeGridWalker(std::istream& in, const std::string& format,
                  std::uint64_t vertex_count, std::string& why)
      : in_(in)
      , ascii_(format == "ascii")
      , big_endian_(format == "binary_big_endian")
      , vertex_count_(vertex_count)
      , why_(why)
  {
  }

  /** Check (or skip) every record of one element. */
  bool element(const PlyElement& element)
  {
    const bool has_list =
        std::any_of(element.properties.begin(), element.properties.end(),
                    [](const PlyProperty& p) { return (p.is_list); });
    if (!ascii_ && !has_list) { // fixed-size records: skip them all at once
      std::uint64_t record = 0;
      for (const PlyProperty& p : element.properties)
        record = addSat(record, p.size);
      in_.seekg(static_cast<std::streamoff>(mulSat(record, element.count)),
                std::ios::cur);
      return (true);
    }
    for (std::uint64_t i = 0; i < element.count; ++i)
      if (!(ascii_ ? asciiRecord(element) : binaryRecord(element)))
        return (false);
    return (true);
  }

private:
  bool fail(const std::string& why)
  {
    why_ = why;
    return (false);
  }

  bool endsInside(const PlyElement& element)
  {
    return (fail("the data ends inside element '" + excerpt(element.name) + "'"));
  }

  bool checkIndex(std::int64_t index)
  {
    if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_count_ ||
        index > std::numeric_limits<std::int32_t>::max())
      return (fail("range_grid vertex index " + std::to_string(index) +
                   " is outside [0, " + std::to_string(vertex_count_) + ")"));
    return (true);
  }

  bool asciiRecord(const PlyElement& element)
  {
    const bool is_grid = element.name == "range_grid";
    if (!std::getline(in_, text_))
      return (endsInside(element));
    while (!text_.empty() && text_.back() == '\r')
      text_.pop_back();
    const std::vector<std::string> tokens = splitWhitespace(text_);
    std::size_t t = 0;
    for (const PlyProperty& p : element.properties) {
      if (!p.is_list) {
        ++t;
        continue;
      }
      std::uint64_t n = 0;
      if (t >= tokens.size() || !parseUnsigned(tokens[t], n) ||
          n > plyTypeMax(p.count_type))
        return (fail("bad list length in element '" + excerpt(element.name) + "'"));
      ++t;
      for (std::uint64_t k = 0; k < n; ++k, ++t) {
        if (t >= tokens.size())
          return (
              fail("a line of element '" + excerpt(element.name) + "' is too short"));
        if (!is_grid)
          continue;
        std::int64_t index = 0;
        const std::string& s = tokens[t];
        const auto r = std::from_chars(s.data(), s.data() + s.size(), index);
        if (r.ec != std::errc() || r.ptr != s.data() + s.size())
          return (
              fail("range_grid vertex index '" + excerpt(s) + "' is not an integer"));
        if (!checkIndex(index))
          return (false);
      }
    }
    if (t != tokens.size())
      return (fail("a line of element '" + excerpt(element.name) + "' has " +
                   std::to_string(tokens.size()) + " values, expected " +
                   std::to_string(t)));
    return (true);
  }

  bool binaryRecord(const PlyElement& element)
  {
    const bool is_grid = element.name == "range_grid";
    for (const PlyProperty& p : element.properties) {
      if (!p.is_list) {
        in_.seekg(static_cast<std::streamoff>(p.size), std::ios::cur);
        continue;
      }
      std::int64_t n = 0;
      if (!readPlyInteger(in_, p.count_type, big_endian_, n) || n < 0)
        return (endsInside(element));
      if (!is_grid) {
        in_.seekg(static_cast<std::streamoff>(
                      mulSat(static_cast<std::uint64_t>(n), plyTypeSize(p.value_type))),
                  std::ios::cur);
        continue;
      }
      for (std::int64_t k = 0; k < n; ++k) {
        std::int64_t index = 0;
        if (!readPlyInteger(in_, p.value_type, big_endian_, index))
          return (endsInside(element));
        if (!checkIndex(index))
          return (false);
      }
    }
    if (!in_)
      return (endsInside(element));
    return (true);
  }

  std::istream& in_;
  const bool ascii_;
  const bool big_endian_;
  const std::uint64_t vertex_count_;
  std::string& why_;
  std::string text_;
};

} // namespace

bool checkPlyRangeGridIndices(const std::string& path, const std::string& format,
                              const std::vector<PlyElement>& elements,
                              std::uint64_t data_offset, std::uint64_t vertex_count,
                              std::string& why)
{
  std::ifstream in(path, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(data_offset));
  if (!in) {
    why = "cannot read the data";
    return (false);
  }
  RangeGridWalker walker(in, format, vertex_count, why);
  for (const PlyElement& element : elements) {
    if (!walker.element(element))
      return (false);
    if (element.name == "range_grid")
      return (true);
  }
  return (true);
}

} // namespace io_detail
} // namespace phaser
} // namespace pcl
