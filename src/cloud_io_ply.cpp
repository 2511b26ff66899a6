/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
// PLY: the header gate in front of PCL's reader, and the binary writer.
#include "cloud_io_detail.h"

#include <pcl/io/ply_io.h>

#include <Eigen/Geometry>

#include <cerrno>
#include <cstdlib>
#include <string>
#include <vector>

/* PLY header gate. PCL's PLY reader sizes its buffer from the vertex count, or from
 * obj_info num_cols x num_rows, before reading any data, and it asserts (aborts: Debian
 * builds PCL with assertions) when more vertices arrive than that buffer holds, when
 * uchar blue comes before red, or on an indented obj_info line. List-valued vertex
 * properties are sized from the first vertex only, so they are refused here. */

namespace pcl {
namespace phaser {
namespace io_detail {

std::uint64_t plyTypeSize(const std::string& type)
{
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8")
    return (1);
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16")
    return (2);
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" ||
      type == "float" || type == "float32")
    return (4);
  if (type == "double" || type == "float64")
    return (8);
  return (0);
}

namespace {

/** What the header of a PLY file says, as far as the gate cares. */
struct PlyHeader {
  std::string format;
  std::vector<PlyElement> elements;
  std::uint64_t num_cols = 0, num_rows = 0;
  std::uint64_t data_offset = 0;
  bool have_end = false;
};

/** What PCL's obj_info handler does with "num_cols N": atoi, then stored as uint32.
 *  Returns false for values atoi cannot represent or negative ones. */
bool parseObjInfoDimension(const std::string& token, std::uint64_t& value)
{
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(token.c_str(), &end, 10);
  if (errno == ERANGE || v < 0 || v > std::numeric_limits<int>::max())
    return (false);
  value = static_cast<std::uint64_t>(v); // no digits: 0, as atoi gives
  return (true);
}

/** A "property ..." line (tokens tok, text for messages) into property. */
bool parsePlyProperty(const std::vector<std::string>& tok, const std::string& text,
                      PlyProperty& property, std::string& why)
{
  if (tok.size() == 5 && tok[1] == "list") {
    property.is_list = true;
    property.count_type = tok[2];
    property.value_type = tok[3];
    property.size = plyTypeSize(tok[2]);
    property.name = tok[4];
    if (property.size != 0 && plyTypeSize(tok[3]) != 0)
      return (true);
  } else if (tok.size() == 3) {
    property.value_type = tok[1];
    property.size = plyTypeSize(tok[1]);
    property.name = tok[2];
    if (property.size != 0)
      return (true);
  } else {
    why = "invalid property line '" + excerpt(text) + "'";
    return (false);
  }
  why = "unknown type in '" + excerpt(text) + "'";
  return (false);
}

/** Parse the header lines after "ply" up to end_header (pos is just past "ply"). */
bool parsePlyHeader(const std::string& prefix, std::size_t pos, PlyHeader& h,
                    std::string& why)
{
  const auto bad = [&](const std::string& message) {
    why = message;
    return (false);
  };
  HeaderLine line;
  for (std::size_t number = 2; nextLine(prefix, pos, line); ++number) {
    // PCL's obj_info handler splits on ' ' and '\t' only and asserts (aborts) when
    // the line does not start with "obj_info": no indentation, no control characters.
    if (hasControlCharacter(line.text))
      return (bad("control character in header line " + std::to_string(number)));
    if (!line.text.empty() && (line.text[0] == ' ' || line.text[0] == '\t'))
      return (bad("header line " + std::to_string(number) + " starts with whitespace"));
    const std::vector<std::string> tok = splitWhitespace(line.text);
    if (tok.empty())
      return (bad("empty header line " + std::to_string(number)));
    const std::string& key = tok[0];
    if (key == "comment")
      continue;
    if (key == "obj_info") {
      if (tok.size() >= 3 && (tok[1] == "num_cols" || tok[1] == "num_rows")) {
        std::uint64_t v = 0;
        if (!parseObjInfoDimension(tok[2], v))
          return (bad("invalid obj_info " + tok[1] + " '" + excerpt(tok[2]) + "'"));
        (tok[1] == "num_cols" ? h.num_cols : h.num_rows) = v;
      }
    } else if (key == "format") {
      if (tok.size() != 3 || (tok[1] != "ascii" && tok[1] != "binary_little_endian" &&
                              tok[1] != "binary_big_endian"))
        return (bad("unsupported format line '" + excerpt(line.text) + "'"));
      if (!h.format.empty() || !h.elements.empty())
        return (bad("misplaced format line"));
      h.format = tok[1];
    } else if (key == "element") {
      if (h.format.empty())
        return (bad("element before the format line"));
      PlyElement element;
      if (tok.size() != 3 || !parseUnsigned(tok[2], element.count))
        return (bad("invalid element line '" + excerpt(line.text) + "'"));
      element.name = tok[1];
      h.elements.push_back(std::move(element));
    } else if (key == "property") {
      if (h.elements.empty())
        return (bad("property before any element"));
      PlyProperty property;
      if (!parsePlyProperty(tok, line.text, property, why))
        return (false);
      h.elements.back().properties.push_back(std::move(property));
    } else if (key == "end_header" && tok.size() == 1) {
      h.data_offset = line.next_offset;
      h.have_end = true;
      return (true);
    } else {
      return (bad("unexpected header line '" + excerpt(line.text) + "'"));
    }
  }
  return (true);
}

/** PCL packs uchar red/green/blue into one 4-byte rgb field: red opens it and blue
 *  writes it and advances. Any other combination misplaces every later write, and a
 *  write past the buffer ends in an assertion (abort). */
bool plyColoursArePackable(const PlyElement& vertex)
{
  int reds = 0, greens = 0, blues = 0;
  std::size_t first_red = 0, first_blue = 0;
  for (std::size_t i = 0; i < vertex.properties.size(); ++i) {
    const PlyProperty& property = vertex.properties[i];
    if (property.value_type != "uchar" && property.value_type != "uint8")
      continue;
    if (property.name == "red" || property.name == "diffuse_red") {
      if (reds++ == 0)
        first_red = i;
    } else if (property.name == "green" || property.name == "diffuse_green") {
      ++greens;
    } else if (property.name == "blue" || property.name == "diffuse_blue") {
      if (blues++ == 0)
        first_blue = i;
    }
  }
  const bool none = reds == 0 && greens == 0 && blues == 0;
  const bool one_each =
      reds == 1 && greens == 1 && blues == 1 && first_red < first_blue;
  return (none || one_each);
}

/** The range_grid element holds one list of 32-bit vertex indices. */
bool isRangeGridIndexList(const PlyElement& range_grid)
{
  const auto& props = range_grid.properties;
  return (props.size() == 1 && props[0].is_list &&
          (props[0].name == "vertex_indices" || props[0].name == "vertex_index") &&
          (props[0].count_type == "uchar" || props[0].count_type == "uint8" ||
           props[0].count_type == "uint" || props[0].count_type == "uint32") &&
          (props[0].value_type == "int" || props[0].value_type == "int32" ||
           props[0].value_type == "uint" || props[0].value_type == "uint32"));
}

bool checkPlyHeader(const std::string& path, std::uintmax_t file_size,
                    std::string* error)
{
  const auto bad = [&](const std::string& why) {
    return (fail(error, quoted(path) + ": not a valid PLY file: " + why));
  };
  std::string prefix;
  if (!readHeaderPrefix(path, file_size, prefix, error))
    return (false);

  std::size_t pos = 0;
  HeaderLine line;
  if (!nextLine(prefix, pos, line) ||
      splitWhitespace(line.text) != std::vector<std::string>{"ply"})
    return (bad("it does not start with the line 'ply'"));
  PlyHeader h;
  std::string why;
  if (!parsePlyHeader(prefix, pos, h, why))
    return (bad(why));
  if (!h.have_end)
    return (bad(prefix.size() >= kMaxHeaderBytes
                    ? std::string("no end_header in the first 1 MiB")
                    : std::string("no end_header (truncated or not a PLY file)")));
  if (h.format.empty())
    return (bad("no format line"));

  const PlyElement* vertex = nullptr;
  const PlyElement* range_grid = nullptr;
  for (const PlyElement& element : h.elements) {
    const bool is_vertex = element.name == "vertex";
    if (!is_vertex && element.name != "range_grid")
      continue;
    const PlyElement*& slot = is_vertex ? vertex : range_grid;
    if (slot)
      return (bad("more than one " + element.name + " element"));
    slot = &element;
  }
  if (!vertex)
    return (bad("no vertex element"));
  bool x = false, y = false, z = false;
  for (const PlyProperty& property : vertex->properties) {
    if (property.is_list)
      return (
          bad("vertex list property '" + excerpt(property.name) + "' (not supported)"));
    x = x || property.name == "x";
    y = y || property.name == "y";
    z = z || property.name == "z";
  }
  if (!(x && y && z))
    return (fail(error, quoted(path) + ": the PLY vertices have no x/y/z properties"));
  if (!plyColoursArePackable(*vertex))
    return (bad("uchar colour properties must be one red, green and blue, red before "
                "blue"));
  if (vertex->count > std::numeric_limits<std::uint32_t>::max())
    return (bad("too many vertices (" + std::to_string(vertex->count) + ")"));

  // PCL lays vertices out in a num_cols x num_rows grid when obj_info gives both.
  const std::string cols = std::to_string(h.num_cols);
  const std::string rows = std::to_string(h.num_rows);
  const bool has_grid = h.num_cols != 0 && h.num_rows != 0;
  const std::uint64_t grid = mulSat(h.num_cols, h.num_rows);
  if (range_grid) {
    if (!has_grid)
      return (bad("range_grid element without obj_info num_cols/num_rows"));
    if (range_grid->count != grid)
      return (bad("range_grid has " + std::to_string(range_grid->count) +
                  " cells but obj_info says " + cols + " x " + rows));
    if (!isRangeGridIndexList(*range_grid))
      return (bad("range_grid must hold one list of 32-bit vertex_indices"));
  }
  if (has_grid && vertex->count > grid)
    return (bad(std::to_string(vertex->count) + " vertices do not fit the obj_info " +
                cols + " x " + rows + " grid"));
  if (has_grid && !range_grid && vertex->count != grid)
    return (bad("obj_info says " + cols + " x " + rows + " but there are " +
                std::to_string(vertex->count) + " vertices"));

  // Minimum body size: binary records have fixed scalar parts (lists at least their
  // count); ascii values take at least one character each.
  std::uint64_t minimum = 0;
  for (const PlyElement& element : h.elements) {
    std::uint64_t per_record = 0;
    for (const PlyProperty& property : element.properties)
      per_record = addSat(per_record, h.format == "ascii" ? 1 : property.size);
    minimum = addSat(minimum, mulSat(element.count, per_record));
  }
  const std::uint64_t available =
      file_size > h.data_offset ? file_size - h.data_offset : 0;
  if (minimum > available)
    return (bad("the header announces at least " + std::to_string(minimum) +
                " bytes of data (" + std::to_string(vertex->count) +
                " vertices) but only " + std::to_string(available) +
                " bytes follow (truncated?)"));
  if (range_grid && !checkPlyRangeGridIndices(path, h.format, h.elements, h.data_offset,
                                              vertex->count, why))
    return (bad(why));
  return (true);
}

} // namespace

bool loadPly(const std::string& path, std::uintmax_t file_size,
             pcl::PCLPointCloud2& cloud, std::string* error)
{
  if (!checkPlyHeader(path, file_size, error))
    return (false);
  pcl::PLYReader reader;
  return (readWithPcl(reader, "PLY", path, cloud, error));
}

bool savePly(const std::string& path, const pcl::PCLPointCloud2& cloud,
             std::string* error)
{
  pcl::PLYWriter writer;
  if (writer.write(path, cloud, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity(),
                   true, false) != 0)
    return (fail(error, quoted(path) + ": PCL's PLY writer failed"));
  return (true);
}

} // namespace io_detail
} // namespace phaser
} // namespace pcl
