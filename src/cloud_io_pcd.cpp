/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
// PCD: the header gate in front of PCL's reader, and the binary writer.
#include "cloud_io_detail.h"

#include <pcl/io/pcd_io.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <string>
#include <vector>

namespace pcl {
namespace phaser {
namespace io_detail {
namespace {

/** LZF expands at most 264 bytes from a 3-byte back-reference (ratio 88); a
 *  binary_compressed PCD claiming more than this ratio is lying. */
constexpr std::uint64_t kMaxLzfRatio = 100;

/** What the header lines of a PCD file say, as far as the gate cares. */
struct PcdHeader {
  std::vector<std::string> names;
  std::vector<std::uint64_t> sizes, counts;
  std::vector<char> types;
  bool have_fields = false, have_size = false, have_type = false, have_count = false;
  bool have_width = false, have_height = false, have_points = false;
  std::uint64_t width = 0, height = 0, points = 0;
  std::string data_type;
  std::uint64_t data_offset = 0;
  bool have_data = false;
};

/** Parse the header lines up to DATA; on a bad line, why says what is wrong. */
bool parsePcdHeader(const std::string& prefix, PcdHeader& h, std::string& why)
{
  HeaderLine line;
  for (std::size_t pos = 0; nextLine(prefix, pos, line);) {
    const std::vector<std::string> tok = splitWhitespace(line.text);
    if (tok.empty() || tok[0][0] == '#')
      continue;
    if (hasControlCharacter(line.text)) {
      why = "control character in the header line '" + excerpt(line.text) + "'";
      return (false);
    }
    const std::string& key = tok[0];
    if (key == "VERSION" || key == "VIEWPOINT")
      continue;
    if (key == "FIELDS" || key == "COLUMNS") {
      h.names.assign(tok.begin() + 1, tok.end());
      h.have_fields = true;
    } else if (key == "SIZE" || key == "COUNT") {
      std::vector<std::uint64_t>& target = key == "SIZE" ? h.sizes : h.counts;
      target.clear();
      for (std::size_t i = 1; i < tok.size(); ++i) {
        std::uint64_t v = 0;
        if (!parseUnsigned(tok[i], v)) {
          why = key + " value '" + excerpt(tok[i]) + "' is not a number";
          return (false);
        }
        target.push_back(v);
      }
      (key == "SIZE" ? h.have_size : h.have_count) = true;
    } else if (key == "TYPE") {
      h.types.clear();
      for (std::size_t i = 1; i < tok.size(); ++i) {
        if (tok[i].size() != 1 ||
            std::string("IUF").find(tok[i][0]) == std::string::npos) {
          why = "TYPE '" + excerpt(tok[i]) + "' is not I, U or F";
          return (false);
        }
        h.types.push_back(tok[i][0]);
      }
      h.have_type = true;
    } else if (key == "WIDTH" || key == "HEIGHT" || key == "POINTS") {
      std::uint64_t v = 0;
      if (tok.size() != 2 || !parseUnsigned(tok[1], v)) {
        why = key + " must be followed by one non-negative integer";
        return (false);
      }
      const bool is_width = key == "WIDTH", is_height = key == "HEIGHT";
      (is_width ? h.width : is_height ? h.height : h.points) = v;
      (is_width ? h.have_width : is_height ? h.have_height : h.have_points) = true;
    } else if (key == "DATA") {
      if (tok.size() < 2) {
        why = "DATA line without a type";
        return (false);
      }
      h.data_type = tok[1];
      h.data_offset = line.next_offset;
      h.have_data = true;
      return (true);
    } else {
      why = "unexpected header line '" + excerpt(line.text) + "'";
      return (false);
    }
  }
  return (true);
}

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
  if (!readHeaderPrefix(path, file_size, prefix, error))
    return (false);
  PcdHeader h;
  std::string why;
  if (!parsePcdHeader(prefix, h, why))
    return (bad(why));

  if (!h.have_data)
    return (bad(prefix.size() >= kMaxHeaderBytes
                    ? std::string("no DATA line in the first 1 MiB")
                    : std::string("no DATA line (truncated or not a PCD file)")));
  const std::string& data_type = h.data_type;
  if (data_type != "ascii" && data_type != "binary" && data_type != "binary_compressed")
    return (bad("unknown DATA type '" + excerpt(data_type) + "'"));
  const std::vector<std::string>& names = h.names;
  if (!h.have_fields || names.empty())
    return (bad("no FIELDS"));
  if (!h.have_size || h.sizes.size() != names.size())
    return (bad("SIZE is missing or does not list one size per field"));
  if (!h.have_type || h.types.size() != names.size())
    return (bad("TYPE is missing or does not list one type per field"));
  if (!h.have_count)
    h.counts.assign(names.size(), 1);
  if (h.counts.size() != names.size())
    return (bad("COUNT does not list one count per field"));
  std::uint64_t point_step = 0, values_per_point = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::uint64_t s = h.sizes[i];
    const char type = h.types[i];
    const bool ok_size =
        type == 'F' ? (s == 4 || s == 8) : (s == 1 || s == 2 || s == 4 || s == 8);
    if (!ok_size)
      return (bad("field '" + excerpt(names[i]) + "' has an invalid SIZE " +
                  std::to_string(s) + " for TYPE " + type));
    if (h.counts[i] == 0 || h.counts[i] > (1u << 20))
      return (bad("field '" + excerpt(names[i]) + "' has an invalid COUNT " +
                  std::to_string(h.counts[i])));
    point_step = addSat(point_step, mulSat(s, h.counts[i]));
    values_per_point = addSat(values_per_point, h.counts[i]);
  }
  const std::uint64_t points = h.points;
  if (!h.have_points)
    return (bad("no POINTS"));
  if (h.have_height && !h.have_width && h.height != 0)
    return (bad("HEIGHT given without WIDTH"));
  const std::uint64_t w = h.have_width ? h.width : points;
  const std::uint64_t ht = (h.have_height && h.height != 0) ? h.height : 1; // as PCL
  if (mulSat(w, ht) != points)
    return (bad("WIDTH x HEIGHT (" + std::to_string(w) + " x " + std::to_string(ht) +
                ") != POINTS (" + std::to_string(points) + ")"));
  if (points > std::numeric_limits<std::uint32_t>::max() ||
      w > std::numeric_limits<std::uint32_t>::max())
    return (bad("too many points (" + std::to_string(points) + ")"));
  if (point_step > std::numeric_limits<std::uint32_t>::max())
    return (bad("points of " + std::to_string(point_step) + " bytes are too large"));

  const std::uint64_t data_offset = h.data_offset;
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
    const auto* raw = reinterpret_cast<const std::uint8_t*>(sizes_raw.data());
    std::uint32_t compressed = 0, uncompressed = 0;
    std::memcpy(&compressed, raw, 4);
    std::memcpy(&uncompressed, raw + 4, 4);
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

} // namespace

bool loadPcd(const std::string& path, std::uintmax_t file_size,
             pcl::PCLPointCloud2& cloud, std::string* error)
{
  if (!checkPcdHeader(path, file_size, error))
    return (false);
  pcl::PCDReader reader;
  return (readWithPcl(reader, "PCD", path, cloud, error));
}

bool savePcd(const std::string& path, const pcl::PCLPointCloud2& cloud,
             std::string* error)
{
  // PCL 1.13's header writer walks the fields in list order and describes the gap
  // between one field and the next as a padding field "_" of COUNT (offset - end of
  // the previous field). A type whose fields are not listed in memory order (in
  // PointXYZINormal, intensity is listed before normal_x but stored after it) thus
  // gets a negative COUNT that no reader accepts. Fields in offset order give the
  // writer only forward gaps, which it pads itself; the data is written unchanged.
  const auto by_offset = [](const pcl::PCLPointField& a, const pcl::PCLPointField& b) {
    return (a.offset < b.offset);
  };
  const pcl::PCLPointCloud2* to_write = &cloud;
  pcl::PCLPointCloud2 sorted;
  if (!std::is_sorted(cloud.fields.begin(), cloud.fields.end(), by_offset)) {
    sorted = cloud;
    std::stable_sort(sorted.fields.begin(), sorted.fields.end(), by_offset);
    to_write = &sorted;
  }
  pcl::PCDWriter writer;
  if (writer.writeBinary(path, *to_write, Eigen::Vector4f::Zero(),
                         Eigen::Quaternionf::Identity()) != 0)
    return (fail(error, quoted(path) + ": PCL's PCD writer failed"));
  return (true);
}

} // namespace io_detail
} // namespace phaser
} // namespace pcl
