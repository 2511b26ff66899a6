/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include <pcl_phaser/cloud_io.h>

#include <pcl/common/io.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <string>
#include <vector>

namespace pcl {
namespace phaser {
namespace {

namespace fs = std::filesystem;

/** Headers longer than this are rejected (real PCD/PLY headers are a few hundred
 *  bytes; the Stanford bunny PLY, with its obj_info block, is about 700). */
constexpr std::size_t kMaxHeaderBytes = 1u << 20;
/** Transform files larger than this are certainly not 16 numbers. */
constexpr std::uintmax_t kMaxTransformFileBytes = 1u << 20;
/** LZF expands at most 264 bytes from a 3-byte back-reference (ratio 88); a
 *  binary_compressed PCD claiming more than this ratio is lying. */
constexpr std::uint64_t kMaxLzfRatio = 100;

bool fail(std::string* error, const std::string& message)
{
  if (error)
    *error = message;
  return (false);
}

std::string quoted(const std::string& path)
{
  return ("'" + path + "'");
}

/** Printable, bounded excerpt of untrusted text for error messages. */
std::string excerpt(const std::string& text, std::size_t max_length = 40)
{
  std::string out;
  for (const char c : text) {
    if (out.size() >= max_length) {
      out += "...";
      break;
    }
    const auto u = static_cast<unsigned char>(c);
    out += (u >= 32 && u < 127) ? c : '?';
  }
  return (out);
}

std::string lowerExtension(const std::string& path)
{
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return (ext);
}

/** a * b, saturating at the largest uint64 instead of wrapping. */
std::uint64_t mulSat(std::uint64_t a, std::uint64_t b)
{
  if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a)
    return (std::numeric_limits<std::uint64_t>::max());
  return (a * b);
}

std::uint64_t addSat(std::uint64_t a, std::uint64_t b)
{
  if (b > std::numeric_limits<std::uint64_t>::max() - a)
    return (std::numeric_limits<std::uint64_t>::max());
  return (a + b);
}

std::vector<std::string> splitWhitespace(const std::string& line)
{
  std::vector<std::string> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i])))
      ++i;
    std::size_t j = i;
    while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j])))
      ++j;
    if (j > i)
      tokens.push_back(line.substr(i, j - i));
    i = j;
  }
  return (tokens);
}

/** Strict decimal unsigned integer: digits only, no sign, no trailing characters. */
bool parseUnsigned(const std::string& token, std::uint64_t& value)
{
  if (token.empty())
    return (false);
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, value);
  return (result.ec == std::errc() && result.ptr == end);
}

/** Control characters other than '\t' ('\r' is stripped from line ends). PCL splits
 *  header lines on ' ', '\t' (and '\r'), so any other whitespace would make it see
 *  different tokens than the checks here. */
bool hasControlCharacter(const std::string& text)
{
  return (std::any_of(text.begin(), text.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return ((u < 32 && c != '\t') || u == 127);
  }));
}

/** One header line and the byte offset just past its '\n'. */
struct HeaderLine {
  std::string text;
  std::size_t next_offset = 0;
};

/** The next line of a header buffer ('\r' stripped), starting at pos; advances pos
 *  past its '\n'. The last line may lack a '\n'. Returns false at the end. */
bool nextLine(const std::string& buffer, std::size_t& pos, HeaderLine& line)
{
  if (pos >= buffer.size())
    return (false);
  std::size_t end = buffer.find('\n', pos);
  const bool has_newline = end != std::string::npos;
  if (!has_newline)
    end = buffer.size();
  line.text = buffer.substr(pos, end - pos);
  while (!line.text.empty() && line.text.back() == '\r')
    line.text.pop_back();
  line.next_offset = has_newline ? end + 1 : end;
  pos = line.next_offset;
  return (true);
}

/** Checks shared by every reader: the path names a readable, non-empty regular
 *  file. Returns its size. */
bool checkInputFile(const std::string& path, std::uintmax_t& size, std::string* error)
{
  if (path.empty())
    return (fail(error, "empty file name"));
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status))
    return (fail(error, quoted(path) + ": no such file"));
  if (fs::is_directory(status))
    return (fail(error, quoted(path) + ": is a directory, not a file"));
  if (!fs::is_regular_file(status))
    return (fail(error, quoted(path) + ": not a regular file"));
  size = fs::file_size(path, ec);
  if (ec)
    return (fail(error,
                 quoted(path) + ": cannot get the file size (" + ec.message() + ")"));
  std::ifstream probe(path, std::ios::binary);
  if (!probe.is_open()) {
    const int err = errno;
    return (fail(error, quoted(path) + ": cannot open for reading (" +
                            std::string(err ? std::strerror(err) : "unknown error") +
                            ")"));
  }
  if (size == 0)
    return (fail(error, quoted(path) + ": file is empty (0 bytes)"));
  return (true);
}

/** Read up to max_bytes from the start of a file, or from offset. */
bool readBytes(const std::string& path, std::uintmax_t offset, std::size_t max_bytes,
               std::string& out)
{
  std::ifstream in(path, std::ios::binary);
  if (!in.is_open())
    return (false);
  in.seekg(static_cast<std::streamoff>(offset));
  if (!in)
    return (false);
  out.assign(max_bytes, '\0');
  in.read(&out[0], static_cast<std::streamsize>(max_bytes));
  out.resize(static_cast<std::size_t>(in.gcount()));
  return (true);
}

/* ------------------------------------------------------------------------------- */
/* PCD header gate. PCL's reader allocates POINTS x point_step while parsing the
 * header and crashes (segfault) on a header without FIELDS, so garbage, an empty file
 * or a lying header can crash it or exhaust memory. Only headers whose announced data
 * fits in the file are passed on. */

bool checkPcdHeader(const std::string& path, std::uintmax_t file_size,
                    std::string* error)
{
  const auto bad = [&](const std::string& why) {
    return (fail(error, quoted(path) + ": not a valid PCD file: " + why));
  };
  std::string prefix;
  const std::size_t want =
      static_cast<std::size_t>(std::min<std::uintmax_t>(file_size, kMaxHeaderBytes));
  if (!readBytes(path, 0, want, prefix))
    return (fail(error, quoted(path) + ": cannot read the header"));

  std::vector<std::string> names;
  std::vector<std::uint64_t> sizes, counts;
  std::vector<char> types;
  bool have_fields = false, have_size = false, have_type = false, have_count = false;
  bool have_width = false, have_height = false, have_points = false;
  std::uint64_t width = 0, height = 0, points = 0;
  std::string data_type;
  std::uint64_t data_offset = 0;
  bool have_data = false;

  HeaderLine line;
  for (std::size_t pos = 0; nextLine(prefix, pos, line);) {
    const std::vector<std::string> tok = splitWhitespace(line.text);
    if (tok.empty() || tok[0][0] == '#')
      continue;
    if (hasControlCharacter(line.text))
      return (bad("control character in the header line '" + excerpt(line.text) + "'"));
    const std::string& key = tok[0];
    if (key == "VERSION" || key == "VIEWPOINT")
      continue;
    if (key == "FIELDS" || key == "COLUMNS") {
      names.assign(tok.begin() + 1, tok.end());
      have_fields = true;
    } else if (key == "SIZE" || key == "COUNT") {
      std::vector<std::uint64_t>& target = key == "SIZE" ? sizes : counts;
      target.clear();
      for (std::size_t i = 1; i < tok.size(); ++i) {
        std::uint64_t v = 0;
        if (!parseUnsigned(tok[i], v))
          return (bad(key + " value '" + excerpt(tok[i]) + "' is not a number"));
        target.push_back(v);
      }
      (key == "SIZE" ? have_size : have_count) = true;
    } else if (key == "TYPE") {
      types.clear();
      for (std::size_t i = 1; i < tok.size(); ++i) {
        if (tok[i].size() != 1 ||
            std::string("IUF").find(tok[i][0]) == std::string::npos)
          return (bad("TYPE '" + excerpt(tok[i]) + "' is not I, U or F"));
        types.push_back(tok[i][0]);
      }
      have_type = true;
    } else if (key == "WIDTH" || key == "HEIGHT" || key == "POINTS") {
      std::uint64_t v = 0;
      if (tok.size() != 2 || !parseUnsigned(tok[1], v))
        return (bad(key + " must be followed by one non-negative integer"));
      if (key == "WIDTH") {
        width = v;
        have_width = true;
      } else if (key == "HEIGHT") {
        height = v;
        have_height = true;
      } else {
        points = v;
        have_points = true;
      }
    } else if (key == "DATA") {
      if (tok.size() < 2)
        return (bad("DATA line without a type"));
      data_type = tok[1];
      data_offset = line.next_offset;
      have_data = true;
      break;
    } else {
      return (bad("unexpected header line '" + excerpt(line.text) + "'"));
    }
  }

  if (!have_data)
    return (bad(prefix.size() >= kMaxHeaderBytes
                    ? std::string("no DATA line in the first 1 MiB")
                    : std::string("no DATA line (truncated or not a PCD file)")));
  if (data_type != "ascii" && data_type != "binary" && data_type != "binary_compressed")
    return (bad("unknown DATA type '" + excerpt(data_type) + "'"));
  if (!have_fields || names.empty())
    return (bad("no FIELDS"));
  if (!have_size || sizes.size() != names.size())
    return (bad("SIZE is missing or does not list one size per field"));
  if (!have_type || types.size() != names.size())
    return (bad("TYPE is missing or does not list one type per field"));
  if (!have_count)
    counts.assign(names.size(), 1);
  if (counts.size() != names.size())
    return (bad("COUNT does not list one count per field"));
  std::uint64_t point_step = 0, values_per_point = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::uint64_t s = sizes[i];
    const bool ok_size =
        types[i] == 'F' ? (s == 4 || s == 8) : (s == 1 || s == 2 || s == 4 || s == 8);
    if (!ok_size)
      return (bad("field '" + excerpt(names[i]) + "' has an invalid SIZE " +
                  std::to_string(s) + " for TYPE " + types[i]));
    if (counts[i] == 0 || counts[i] > (1u << 20))
      return (bad("field '" + excerpt(names[i]) + "' has an invalid COUNT " +
                  std::to_string(counts[i])));
    point_step = addSat(point_step, mulSat(s, counts[i]));
    values_per_point = addSat(values_per_point, counts[i]);
  }
  if (!have_points)
    return (bad("no POINTS"));
  if (have_height && !have_width && height != 0)
    return (bad("HEIGHT given without WIDTH"));
  const std::uint64_t w = have_width ? width : points;
  const std::uint64_t h = (have_height && height != 0) ? height : 1; // as PCL does
  if (mulSat(w, h) != points)
    return (bad("WIDTH x HEIGHT (" + std::to_string(w) + " x " + std::to_string(h) +
                ") != POINTS (" + std::to_string(points) + ")"));
  if (points > std::numeric_limits<std::uint32_t>::max() ||
      w > std::numeric_limits<std::uint32_t>::max())
    return (bad("too many points (" + std::to_string(points) + ")"));
  if (point_step > std::numeric_limits<std::uint32_t>::max())
    return (bad("points of " + std::to_string(point_step) + " bytes are too large"));

  const std::uint64_t available = file_size > data_offset ? file_size - data_offset : 0;
  const std::uint64_t data_bytes = mulSat(points, point_step);
  if (points == 0)
    return (true);
  if (data_type == "ascii") {
    // Every value needs at least one character.
    if (mulSat(points, values_per_point) > available)
      return (bad("the header announces " + std::to_string(points) +
                  " points but only " + std::to_string(available) +
                  " bytes of ascii data follow (truncated?)"));
  } else if (data_type == "binary") {
    if (data_bytes > available)
      return (bad("the header announces " + std::to_string(points) + " points (" +
                  std::to_string(data_bytes) + " bytes) but only " +
                  std::to_string(available) + " bytes of data follow (truncated?)"));
  } else {
    std::string sizes_raw;
    if (available < 8 || !readBytes(path, data_offset, 8, sizes_raw) ||
        sizes_raw.size() != 8)
      return (bad("binary_compressed data is missing its size block (truncated?)"));
    std::uint32_t compressed = 0, uncompressed = 0;
    std::memcpy(&compressed, sizes_raw.data(), 4);
    std::memcpy(&uncompressed, sizes_raw.data() + 4, 4);
    if (compressed > available - 8)
      return (bad("binary_compressed block of " + std::to_string(compressed) +
                  " bytes but only " + std::to_string(available - 8) +
                  " bytes follow (truncated?)"));
    if (uncompressed != data_bytes)
      return (bad("binary_compressed block decompresses to " +
                  std::to_string(uncompressed) + " bytes, the header needs " +
                  std::to_string(data_bytes)));
    if (data_bytes > addSat(mulSat(compressed, kMaxLzfRatio), 1024))
      return (bad("binary_compressed block is too small to hold " +
                  std::to_string(data_bytes) + " bytes"));
  }
  return (true);
}

/* ------------------------------------------------------------------------------- */
/* PLY header gate. PCL's PLY reader sizes its buffer from the vertex count, or from
 * obj_info num_cols x num_rows, before reading any data, and it asserts (aborts: Debian
 * builds PCL with assertions) when more vertices arrive than that buffer holds, when
 * uchar blue comes before red, or on an indented obj_info line. List-valued vertex
 * properties are sized from the first vertex only, so they are refused here. */

struct PlyProperty {
  bool is_list = false;
  std::uint64_t size = 0; // scalar bytes, or bytes of the list's count
  std::string count_type; // list only
  std::string value_type; // list only (scalar type for scalars)
  std::string name;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

/** Bytes of a PLY scalar type, 0 if unknown. */
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

/** Walk a PLY body up to its range_grid element and check that every range_grid
 *  vertex index is in [0, vertex_count). PCL computes index * point_step in 32 bits,
 *  so a crafted index wraps its bounds check and PCL reads gigabytes out of bounds
 *  (segfault). Ascii bodies must hold one element per line. */
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
  const bool ascii = format == "ascii";
  const bool big_endian = format == "binary_big_endian";
  const auto checkIndex = [&](std::int64_t index) {
    if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_count ||
        index > std::numeric_limits<std::int32_t>::max()) {
      why = "range_grid vertex index " + std::to_string(index) + " is outside [0, " +
            std::to_string(vertex_count) + ")";
      return (false);
    }
    return (true);
  };
  std::string text;
  for (const PlyElement& element : elements) {
    const bool is_grid = element.name == "range_grid";
    const bool has_list =
        std::any_of(element.properties.begin(), element.properties.end(),
                    [](const PlyProperty& p) { return (p.is_list); });
    if (!ascii && !has_list) { // fixed-size records: skip them all at once
      std::uint64_t record = 0;
      for (const PlyProperty& p : element.properties)
        record = addSat(record, p.size);
      in.seekg(static_cast<std::streamoff>(mulSat(record, element.count)),
               std::ios::cur);
      continue;
    }
    for (std::uint64_t i = 0; i < element.count; ++i) {
      if (ascii) {
        if (!std::getline(in, text)) {
          why = "the data ends inside element '" + excerpt(element.name) + "'";
          return (false);
        }
        while (!text.empty() && text.back() == '\r')
          text.pop_back();
        const std::vector<std::string> tokens = splitWhitespace(text);
        std::size_t t = 0;
        for (const PlyProperty& p : element.properties) {
          if (!p.is_list) {
            ++t;
            continue;
          }
          std::uint64_t n = 0;
          if (t >= tokens.size() || !parseUnsigned(tokens[t], n) ||
              n > plyTypeMax(p.count_type)) {
            why = "bad list length in element '" + excerpt(element.name) + "'";
            return (false);
          }
          ++t;
          for (std::uint64_t k = 0; k < n; ++k, ++t) {
            if (t >= tokens.size()) {
              why = "a line of element '" + excerpt(element.name) + "' is too short";
              return (false);
            }
            if (is_grid) {
              std::int64_t index = 0;
              const std::string& s = tokens[t];
              const auto r = std::from_chars(s.data(), s.data() + s.size(), index);
              if (r.ec != std::errc() || r.ptr != s.data() + s.size()) {
                why = "range_grid vertex index '" + excerpt(s) + "' is not an integer";
                return (false);
              }
              if (!checkIndex(index))
                return (false);
            }
          }
        }
        if (t != tokens.size()) {
          why = "a line of element '" + excerpt(element.name) + "' has " +
                std::to_string(tokens.size()) + " values, expected " +
                std::to_string(t);
          return (false);
        }
      } else {
        for (const PlyProperty& p : element.properties) {
          if (!p.is_list) {
            in.seekg(static_cast<std::streamoff>(p.size), std::ios::cur);
            continue;
          }
          std::int64_t n = 0;
          if (!readPlyInteger(in, p.count_type, big_endian, n) || n < 0) {
            why = "the data ends inside element '" + excerpt(element.name) + "'";
            return (false);
          }
          if (!is_grid) {
            in.seekg(static_cast<std::streamoff>(mulSat(static_cast<std::uint64_t>(n),
                                                        plyTypeSize(p.value_type))),
                     std::ios::cur);
            continue;
          }
          for (std::int64_t k = 0; k < n; ++k) {
            std::int64_t index = 0;
            if (!readPlyInteger(in, p.value_type, big_endian, index)) {
              why = "the data ends inside element 'range_grid'";
              return (false);
            }
            if (!checkIndex(index))
              return (false);
          }
        }
        if (!in) {
          why = "the data ends inside element '" + excerpt(element.name) + "'";
          return (false);
        }
      }
    }
    if (is_grid)
      return (true);
  }
  return (true);
}

bool checkPlyHeader(const std::string& path, std::uintmax_t file_size,
                    std::string* error)
{
  const auto bad = [&](const std::string& why) {
    return (fail(error, quoted(path) + ": not a valid PLY file: " + why));
  };
  std::string prefix;
  const std::size_t want =
      static_cast<std::size_t>(std::min<std::uintmax_t>(file_size, kMaxHeaderBytes));
  if (!readBytes(path, 0, want, prefix))
    return (fail(error, quoted(path) + ": cannot read the header"));

  std::size_t pos = 0;
  HeaderLine line;
  if (!nextLine(prefix, pos, line) ||
      splitWhitespace(line.text) != std::vector<std::string>{"ply"})
    return (bad("it does not start with the line 'ply'"));

  std::string format;
  std::vector<PlyElement> elements;
  std::uint64_t num_cols = 0, num_rows = 0;
  std::uint64_t data_offset = 0;
  bool have_end = false;
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
        (tok[1] == "num_cols" ? num_cols : num_rows) = v;
      }
      continue;
    }
    if (key == "format") {
      if (tok.size() != 3 || (tok[1] != "ascii" && tok[1] != "binary_little_endian" &&
                              tok[1] != "binary_big_endian"))
        return (bad("unsupported format line '" + excerpt(line.text) + "'"));
      if (!format.empty() || !elements.empty())
        return (bad("misplaced format line"));
      format = tok[1];
      continue;
    }
    if (key == "element") {
      if (format.empty())
        return (bad("element before the format line"));
      PlyElement element;
      if (tok.size() != 3 || !parseUnsigned(tok[2], element.count))
        return (bad("invalid element line '" + excerpt(line.text) + "'"));
      element.name = tok[1];
      elements.push_back(std::move(element));
      continue;
    }
    if (key == "property") {
      if (elements.empty())
        return (bad("property before any element"));
      PlyProperty property;
      if (tok.size() == 5 && tok[1] == "list") {
        property.is_list = true;
        property.count_type = tok[2];
        property.value_type = tok[3];
        property.size = plyTypeSize(tok[2]);
        property.name = tok[4];
        if (property.size == 0 || plyTypeSize(tok[3]) == 0)
          return (bad("unknown type in '" + excerpt(line.text) + "'"));
      } else if (tok.size() == 3) {
        property.value_type = tok[1];
        property.size = plyTypeSize(tok[1]);
        property.name = tok[2];
        if (property.size == 0)
          return (bad("unknown type in '" + excerpt(line.text) + "'"));
      } else {
        return (bad("invalid property line '" + excerpt(line.text) + "'"));
      }
      elements.back().properties.push_back(std::move(property));
      continue;
    }
    if (key == "end_header" && tok.size() == 1) {
      data_offset = line.next_offset;
      have_end = true;
      break;
    }
    return (bad("unexpected header line '" + excerpt(line.text) + "'"));
  }
  if (!have_end)
    return (bad(prefix.size() >= kMaxHeaderBytes
                    ? std::string("no end_header in the first 1 MiB")
                    : std::string("no end_header (truncated or not a PLY file)")));
  if (format.empty())
    return (bad("no format line"));

  const PlyElement* vertex = nullptr;
  const PlyElement* range_grid = nullptr;
  for (const PlyElement& element : elements) {
    if (element.name == "vertex") {
      if (vertex)
        return (bad("more than one vertex element"));
      vertex = &element;
    } else if (element.name == "range_grid") {
      if (range_grid)
        return (bad("more than one range_grid element"));
      range_grid = &element;
    }
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
  // PCL packs uchar red/green/blue into one 4-byte rgb field: red opens it and blue
  // writes it and advances. Any other combination misplaces every later write, and a
  // write past the buffer ends in an assertion (abort).
  {
    int reds = 0, greens = 0, blues = 0;
    std::size_t first_red = 0, first_blue = 0;
    for (std::size_t i = 0; i < vertex->properties.size(); ++i) {
      const PlyProperty& property = vertex->properties[i];
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
    if (!none && !one_each)
      return (bad("uchar colour properties must be one red, green and blue, red before "
                  "blue"));
  }
  if (vertex->count > std::numeric_limits<std::uint32_t>::max())
    return (bad("too many vertices (" + std::to_string(vertex->count) + ")"));

  // PCL lays vertices out in a num_cols x num_rows grid when obj_info gives both.
  const bool has_grid = num_cols != 0 && num_rows != 0;
  const std::uint64_t grid = mulSat(num_cols, num_rows);
  if (range_grid) {
    if (!has_grid)
      return (bad("range_grid element without obj_info num_cols/num_rows"));
    if (range_grid->count != grid)
      return (bad("range_grid has " + std::to_string(range_grid->count) +
                  " cells but obj_info says " + std::to_string(num_cols) + " x " +
                  std::to_string(num_rows)));
    const auto& props = range_grid->properties;
    const bool ok_list =
        props.size() == 1 && props[0].is_list &&
        (props[0].name == "vertex_indices" || props[0].name == "vertex_index") &&
        (props[0].count_type == "uchar" || props[0].count_type == "uint8" ||
         props[0].count_type == "uint" || props[0].count_type == "uint32") &&
        (props[0].value_type == "int" || props[0].value_type == "int32" ||
         props[0].value_type == "uint" || props[0].value_type == "uint32");
    if (!ok_list)
      return (bad("range_grid must hold one list of 32-bit vertex_indices"));
  }
  if (has_grid && vertex->count > grid)
    return (bad(std::to_string(vertex->count) + " vertices do not fit the obj_info " +
                std::to_string(num_cols) + " x " + std::to_string(num_rows) + " grid"));
  if (has_grid && !range_grid && vertex->count != grid)
    return (bad("obj_info says " + std::to_string(num_cols) + " x " +
                std::to_string(num_rows) + " but there are " +
                std::to_string(vertex->count) + " vertices"));

  // Minimum body size: binary records have fixed scalar parts (lists at least their
  // count); ascii values take at least one character each.
  std::uint64_t minimum = 0;
  for (const PlyElement& element : elements) {
    std::uint64_t per_record = 0;
    for (const PlyProperty& property : element.properties)
      per_record = addSat(per_record, format == "ascii" ? 1 : property.size);
    minimum = addSat(minimum, mulSat(element.count, per_record));
  }
  const std::uint64_t available = file_size > data_offset ? file_size - data_offset : 0;
  if (minimum > available)
    return (bad("the header announces at least " + std::to_string(minimum) +
                " bytes of data (" + std::to_string(vertex->count) +
                " vertices) but only " + std::to_string(available) +
                " bytes follow (truncated?)"));
  if (range_grid) {
    std::string why;
    if (!checkPlyRangeGridIndices(path, format, elements, data_offset, vertex->count,
                                  why))
      return (bad(why));
  }
  return (true);
}

/* ------------------------------------------------------------------------------- */

bool findField(const pcl::PCLPointCloud2& cloud, const std::string& name,
               const pcl::PCLPointField*& field)
{
  for (const auto& f : cloud.fields)
    if (f.name == name) {
      field = &f;
      return (true);
    }
  return (false);
}

std::string fieldList(const pcl::PCLPointCloud2& cloud)
{
  std::string list;
  for (const auto& f : cloud.fields)
    list += (list.empty() ? "" : " ") + f.name;
  return (list.empty() ? std::string("none") : list);
}

/** Structural consistency of a blob: known field types inside point_step, and data
 *  holding exactly width * height * point_step bytes. */
bool checkBlobLayout(const pcl::PCLPointCloud2& cloud, std::string& why)
{
  if (cloud.fields.empty()) {
    why = "the cloud has no fields";
    return (false);
  }
  for (const auto& f : cloud.fields) {
    const int size = pcl::getFieldSize(f.datatype);
    if (size == 0) {
      why = "field '" + excerpt(f.name) + "' has an unknown data type";
      return (false);
    }
    const std::uint64_t end = addSat(
        f.offset, mulSat(static_cast<std::uint64_t>(size), std::max(1u, f.count)));
    if (end > cloud.point_step) {
      why = "field '" + excerpt(f.name) + "' lies outside the point (point_step " +
            std::to_string(cloud.point_step) + ")";
      return (false);
    }
  }
  const std::uint64_t expected =
      mulSat(mulSat(cloud.width, cloud.height), cloud.point_step);
  if (expected != cloud.data.size()) {
    why = "inconsistent cloud: " + std::to_string(cloud.width) + " x " +
          std::to_string(cloud.height) + " points of " +
          std::to_string(cloud.point_step) + " bytes need " + std::to_string(expected) +
          " bytes, data holds " + std::to_string(cloud.data.size());
    return (false);
  }
  return (true);
}

/** Every point has finite x, y and z (float fields; integer coordinates always are). */
bool allXYZFinite(const pcl::PCLPointCloud2& cloud)
{
  const std::size_t n = static_cast<std::size_t>(cloud.width) * cloud.height;
  if (n == 0)
    return (true);
  for (const char* name : {"x", "y", "z"}) {
    const pcl::PCLPointField* f = nullptr;
    if (!findField(cloud, name, f))
      continue;
    const std::uint8_t* base = cloud.data.data() + f->offset;
    if (f->datatype == pcl::PCLPointField::FLOAT32) {
      for (std::size_t i = 0; i < n; ++i) {
        float v;
        std::memcpy(&v, base + i * cloud.point_step, sizeof(v));
        if (!std::isfinite(v))
          return (false);
      }
    } else if (f->datatype == pcl::PCLPointField::FLOAT64) {
      for (std::size_t i = 0; i < n; ++i) {
        double v;
        std::memcpy(&v, base + i * cloud.point_step, sizeof(v));
        if (!std::isfinite(v))
          return (false);
      }
    }
  }
  return (true);
}

/** Validate what a reader produced and normalise row_step / is_dense. */
bool finishLoadedCloud(const std::string& path, pcl::PCLPointCloud2& cloud,
                       std::string* error)
{
  std::string why;
  if (!checkBlobLayout(cloud, why))
    return (fail(error, quoted(path) + ": " + why));
  const pcl::PCLPointField* f = nullptr;
  if (!findField(cloud, "x", f) || !findField(cloud, "y", f) ||
      !findField(cloud, "z", f))
    return (fail(error, quoted(path) + ": the cloud has no x/y/z fields (fields: " +
                            fieldList(cloud) + ")"));
  cloud.row_step = cloud.point_step * cloud.width;
  cloud.is_dense = (cloud.is_dense != 0 && allXYZFinite(cloud)) ? 1 : 0;
  return (true);
}

bool hostIsLittleEndian()
{
  const std::uint16_t probe = 1;
  std::uint8_t first;
  std::memcpy(&first, &probe, 1);
  return (first == 1);
}

pcl::PCLPointField makeFloatField(const std::string& name, std::uint32_t offset)
{
  pcl::PCLPointField field;
  field.name = name;
  field.offset = offset;
  field.datatype = pcl::PCLPointField::FLOAT32;
  field.count = 1;
  return (field);
}

bool loadKittiBin(const std::string& path, std::uintmax_t file_size,
                  pcl::PCLPointCloud2& cloud, std::string* error)
{
  constexpr std::uintmax_t kRecord = 16;
  if (file_size % kRecord != 0)
    return (fail(error, quoted(path) + ": not a KITTI .bin scan: its size (" +
                            std::to_string(file_size) +
                            " bytes) is not a multiple of 16 (4 float32 per point)"));
  const std::uintmax_t n = file_size / kRecord;
  if (file_size > std::numeric_limits<std::uint32_t>::max()) // row_step is 32-bit
    return (fail(error, quoted(path) + ": too many points for one cloud (" +
                            std::to_string(n) + ")"));

  cloud = pcl::PCLPointCloud2();
  cloud.fields = {makeFloatField("x", 0), makeFloatField("y", 4),
                  makeFloatField("z", 8), makeFloatField("intensity", 12)};
  cloud.point_step = kRecord;
  cloud.width = static_cast<std::uint32_t>(n);
  cloud.height = 1;
  cloud.row_step = static_cast<std::uint32_t>(kRecord * n);
  cloud.is_bigendian = false;
  cloud.data.resize(static_cast<std::size_t>(file_size));

  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(cloud.data.data()),
          static_cast<std::streamsize>(file_size));
  if (!in || static_cast<std::uintmax_t>(in.gcount()) != file_size)
    return (fail(error, quoted(path) + ": read error (file shorter than reported?)"));
  if (!hostIsLittleEndian())
    for (std::size_t i = 0; i + 4 <= cloud.data.size(); i += 4) {
      std::swap(cloud.data[i], cloud.data[i + 3]);
      std::swap(cloud.data[i + 1], cloud.data[i + 2]);
    }
  cloud.is_dense = allXYZFinite(cloud) ? 1 : 0;
  return (true);
}

bool loadCloudUnguarded(const std::string& path, pcl::PCLPointCloud2& cloud,
                        std::string* error)
{
  std::uintmax_t size = 0;
  if (!checkInputFile(path, size, error))
    return (false);
  const CloudFormat format = getCloudFormat(path);
  switch (format) {
  case CloudFormat::KITTI_BIN:
    return (loadKittiBin(path, size, cloud, error));
  case CloudFormat::PCD: {
    if (!checkPcdHeader(path, size, error))
      return (false);
    cloud = pcl::PCLPointCloud2();
    pcl::PCDReader reader;
    if (reader.read(path, cloud) < 0)
      return (fail(error, quoted(path) + ": PCL's PCD reader rejected the file " +
                              "(malformed or truncated data)"));
    return (finishLoadedCloud(path, cloud, error));
  }
  case CloudFormat::PLY: {
    if (!checkPlyHeader(path, size, error))
      return (false);
    cloud = pcl::PCLPointCloud2();
    pcl::PLYReader reader;
    if (reader.read(path, cloud) < 0)
      return (fail(error, quoted(path) + ": PCL's PLY reader rejected the file " +
                              "(malformed or truncated data)"));
    return (finishLoadedCloud(path, cloud, error));
  }
  case CloudFormat::UNKNOWN:
    break;
  }
  const std::string ext = fs::path(path).extension().string();
  return (
      fail(error, quoted(path) + ": " +
                      (ext.empty() ? std::string("no file extension")
                                   : "unsupported extension '" + excerpt(ext) + "'") +
                      " (expected .pcd, .ply or .bin)"));
}

/* ------------------------------------------------------------------------------- */

/** A field value as float, whatever its stored type (host byte order). */
float readAsFloat(const std::uint8_t* p, std::uint8_t datatype)
{
  switch (datatype) {
  case pcl::PCLPointField::INT8: {
    std::int8_t v;
    std::memcpy(&v, p, sizeof(v));
    return (static_cast<float>(v));
  }
  case pcl::PCLPointField::UINT8:
    return (static_cast<float>(*p));
  case pcl::PCLPointField::INT16: {
    std::int16_t v;
    std::memcpy(&v, p, sizeof(v));
    return (static_cast<float>(v));
  }
  case pcl::PCLPointField::UINT16: {
    std::uint16_t v;
    std::memcpy(&v, p, sizeof(v));
    return (static_cast<float>(v));
  }
  case pcl::PCLPointField::INT32: {
    std::int32_t v;
    std::memcpy(&v, p, sizeof(v));
    return (static_cast<float>(v));
  }
  case pcl::PCLPointField::UINT32: {
    std::uint32_t v;
    std::memcpy(&v, p, sizeof(v));
    return (static_cast<float>(v));
  }
  case pcl::PCLPointField::INT64: {
    std::int64_t v;
    std::memcpy(&v, p, sizeof(v));
    return (static_cast<float>(v));
  }
  case pcl::PCLPointField::UINT64: {
    std::uint64_t v;
    std::memcpy(&v, p, sizeof(v));
    return (static_cast<float>(v));
  }
  case pcl::PCLPointField::FLOAT32: {
    float v;
    std::memcpy(&v, p, sizeof(v));
    return (v);
  }
  case pcl::PCLPointField::FLOAT64: {
    double v;
    std::memcpy(&v, p, sizeof(v));
    return (static_cast<float>(v));
  }
  default:
    return (0.0f);
  }
}

bool saveKittiBin(const std::string& path, const pcl::PCLPointCloud2& cloud,
                  std::string* error)
{
  const pcl::PCLPointField* fx = nullptr;
  const pcl::PCLPointField* fy = nullptr;
  const pcl::PCLPointField* fz = nullptr;
  const pcl::PCLPointField* fi = nullptr;
  findField(cloud, "x", fx);
  findField(cloud, "y", fy);
  findField(cloud, "z", fz);
  findField(cloud, "intensity", fi);
  const std::size_t n = static_cast<std::size_t>(cloud.width) * cloud.height;
  std::vector<float> out(4 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* point = cloud.data.data() + i * cloud.point_step;
    out[4 * i + 0] = readAsFloat(point + fx->offset, fx->datatype);
    out[4 * i + 1] = readAsFloat(point + fy->offset, fy->datatype);
    out[4 * i + 2] = readAsFloat(point + fz->offset, fz->datatype);
    out[4 * i + 3] = fi ? readAsFloat(point + fi->offset, fi->datatype) : 0.0f;
  }
  if (!hostIsLittleEndian())
    for (float& v : out) {
      std::uint8_t b[4];
      std::memcpy(b, &v, 4);
      std::swap(b[0], b[3]);
      std::swap(b[1], b[2]);
      std::memcpy(&v, b, 4);
    }
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file.is_open()) {
    const int err = errno;
    return (fail(error, quoted(path) + ": cannot open for writing (" +
                            std::string(err ? std::strerror(err) : "unknown error") +
                            ")"));
  }
  file.write(reinterpret_cast<const char*>(out.data()),
             static_cast<std::streamsize>(out.size() * sizeof(float)));
  file.close();
  if (!file)
    return (fail(error, quoted(path) + ": write error"));
  return (true);
}

bool saveCloudUnguarded(const std::string& path, const pcl::PCLPointCloud2& cloud,
                        std::string* error)
{
  if (path.empty())
    return (fail(error, "empty file name"));
  const CloudFormat format = getCloudFormat(path);
  if (format == CloudFormat::UNKNOWN) {
    const std::string ext = fs::path(path).extension().string();
    return (
        fail(error, quoted(path) + ": " +
                        (ext.empty() ? std::string("no file extension")
                                     : "unsupported extension '" + excerpt(ext) + "'") +
                        " (expected .pcd, .ply or .bin)"));
  }
  std::error_code ec;
  if (fs::is_directory(path, ec))
    return (fail(error, quoted(path) + ": is a directory"));
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent, ec))
    return (fail(error, quoted(path) + ": directory " + quoted(parent.string()) +
                            " does not exist"));
  std::string why;
  if (!checkBlobLayout(cloud, why))
    return (fail(error, quoted(path) + ": cannot save: " + why));
  if (cloud.width * static_cast<std::uint64_t>(cloud.height) == 0)
    return (fail(error, quoted(path) + ": cannot save an empty cloud"));
  const pcl::PCLPointField* f = nullptr;
  if (!findField(cloud, "x", f) || !findField(cloud, "y", f) ||
      !findField(cloud, "z", f))
    return (fail(error, quoted(path) + ": cannot save: the cloud has no x/y/z fields " +
                            "(fields: " + fieldList(cloud) + ")"));

  const Eigen::Vector4f origin = Eigen::Vector4f::Zero();
  const Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
  switch (format) {
  case CloudFormat::PCD: {
    pcl::PCDWriter writer;
    if (writer.writeBinary(path, cloud, origin, orientation) != 0)
      return (fail(error, quoted(path) + ": PCL's PCD writer failed"));
    return (true);
  }
  case CloudFormat::PLY: {
    pcl::PLYWriter writer;
    if (writer.write(path, cloud, origin, orientation, true, false) != 0)
      return (fail(error, quoted(path) + ": PCL's PLY writer failed"));
    return (true);
  }
  case CloudFormat::KITTI_BIN:
    return (saveKittiBin(path, cloud, error));
  case CloudFormat::UNKNOWN:
    break;
  }
  return (fail(error, quoted(path) + ": unsupported format"));
}

std::string formatNumber(double value)
{
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.3g", value);
  return (buffer);
}

} // namespace

/* ------------------------------------------------------------------------------- */

CloudFormat getCloudFormat(const std::string& path)
{
  const std::string ext = lowerExtension(path);
  if (ext == ".pcd")
    return (CloudFormat::PCD);
  if (ext == ".ply")
    return (CloudFormat::PLY);
  if (ext == ".bin")
    return (CloudFormat::KITTI_BIN);
  return (CloudFormat::UNKNOWN);
}

bool loadCloud(const std::string& path, pcl::PCLPointCloud2& cloud, std::string* error)
{
  try {
    return (loadCloudUnguarded(path, cloud, error));
  } catch (const std::bad_alloc&) {
    return (fail(error, quoted(path) + ": out of memory while reading"));
  } catch (const std::exception& e) {
    return (fail(error, quoted(path) + ": read error: " + excerpt(e.what(), 200)));
  } catch (...) {
    return (fail(error, quoted(path) + ": read error (unknown exception)"));
  }
}

bool saveCloud(const std::string& path, const pcl::PCLPointCloud2& cloud,
               std::string* error)
{
  try {
    return (saveCloudUnguarded(path, cloud, error));
  } catch (const std::bad_alloc&) {
    return (fail(error, quoted(path) + ": out of memory while writing"));
  } catch (const std::exception& e) {
    return (fail(error, quoted(path) + ": write error: " + excerpt(e.what(), 200)));
  } catch (...) {
    return (fail(error, quoted(path) + ": write error (unknown exception)"));
  }
}

CloudFieldInfo getCloudFieldInfo(const pcl::PCLPointCloud2& cloud)
{
  CloudFieldInfo info;
  for (const auto& f : cloud.fields)
    info.names.push_back(f.name);
  const auto has = [&](const char* name) { return (hasField(cloud, name)); };
  info.has_xyz = has("x") && has("y") && has("z");
  info.has_intensity = has("intensity");
  info.has_rgb = has("rgb") || has("rgba");
  info.has_normals = has("normal_x") && has("normal_y") && has("normal_z");
  return (info);
}

bool hasField(const pcl::PCLPointCloud2& cloud, const std::string& name)
{
  const pcl::PCLPointField* f = nullptr;
  return (findField(cloud, name, f));
}

bool parseTransform(const std::string& text, Eigen::Matrix4d& transform,
                    std::string* error, double tolerance)
{
  if (!std::isfinite(tolerance) || tolerance < 0.0)
    return (fail(error,
                 "tolerance must be finite and >= 0, got " + formatNumber(tolerance)));
  std::vector<double> values;
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
  std::ofstream file(path, std::ios::trunc);
  if (!file.is_open()) {
    const int err = errno;
    return (fail(error, quoted(path) + ": cannot open for writing (" +
                            std::string(err ? std::strerror(err) : "unknown error") +
                            ")"));
  }
  file << text;
  file.close();
  if (!file)
    return (fail(error, quoted(path) + ": write error"));
  return (true);
}

namespace detail {

bool checkFloatXYZ(const pcl::PCLPointCloud2& cloud, const std::string& path,
                   std::string* error)
{
  for (const char* name : {"x", "y", "z"}) {
    const pcl::PCLPointField* f = nullptr;
    if (!findField(cloud, name, f))
      return (fail(error, quoted(path) + ": the cloud has no '" + name + "' field"));
    if (f->datatype != pcl::PCLPointField::FLOAT32 || f->count != 1)
      return (fail(error, quoted(path) + ": field '" + name + "' is stored as " +
                              std::to_string(f->count) + " x " +
                              std::to_string(pcl::getFieldSize(f->datatype) * 8) +
                              "-bit " +
                              (f->datatype == pcl::PCLPointField::FLOAT32 ||
                                       f->datatype == pcl::PCLPointField::FLOAT64
                                   ? "float"
                                   : "integer") +
                              ", but the point type needs one float32; load into a "
                              "pcl::PCLPointCloud2 and convert instead"));
  }
  return (true);
}

} // namespace detail
} // namespace phaser
} // namespace pcl
