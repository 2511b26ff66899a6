/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
// Byte, string, file and field helpers shared by the cloud_io*.cpp files.
#include "cloud_io_detail.h"

#include <pcl/common/io.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <utility>

namespace pcl {
namespace phaser {
namespace io_detail {

namespace fs = std::filesystem;

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

std::string excerpt(const std::string& text, std::size_t max_length)
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

std::string unsupportedExtensionMessage(const std::string& path)
{
  const std::string ext = fs::path(path).extension().string();
  return (quoted(path) + ": " +
          (ext.empty() ? std::string("no file extension")
                       : "unsupported extension '" + excerpt(ext) + "'") +
          " (expected .pcd, .ply or .bin)");
}

std::string openErrorMessage(const std::string& path, const char* what)
{
  const int err = errno;
  return (quoted(path) + ": cannot open for " + what + " (" +
          std::string(err ? std::strerror(err) : "unknown error") + ")");
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

bool parseUnsigned(const std::string& token, std::uint64_t& value)
{
  if (token.empty())
    return (false);
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, value);
  return (result.ec == std::errc() && result.ptr == end);
}

bool hasControlCharacter(const std::string& text)
{
  return (std::any_of(text.begin(), text.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return ((u < 32 && c != '\t') || u == 127);
  }));
}

/* ---------------------------------- files -------------------------------------- */

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
  if (!probe.is_open())
    return (fail(error, openErrorMessage(path, "reading")));
  if (size == 0)
    return (fail(error, quoted(path) + ": file is empty (0 bytes)"));
  return (true);
}

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

bool readHeaderPrefix(const std::string& path, std::uintmax_t file_size,
                      std::string& prefix, std::string* error)
{
  const std::size_t want =
      static_cast<std::size_t>(std::min<std::uintmax_t>(file_size, kMaxHeaderBytes));
  if (!readBytes(path, 0, want, prefix))
    return (fail(error, quoted(path) + ": cannot read the header"));
  return (true);
}

bool writeFile(const std::string& path, const void* data, std::size_t size, bool binary,
               std::string* error)
{
  std::ofstream file(path,
                     binary ? std::ios::binary | std::ios::trunc : std::ios::trunc);
  if (!file.is_open())
    return (fail(error, openErrorMessage(path, "writing")));
  file.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  file.close();
  if (!file)
    return (fail(error, quoted(path) + ": write error"));
  return (true);
}

/* ---------------------------------- blobs -------------------------------------- */

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

bool hasXYZFields(const pcl::PCLPointCloud2& cloud)
{
  const pcl::PCLPointField* f = nullptr;
  return (findField(cloud, "x", f) && findField(cloud, "y", f) &&
          findField(cloud, "z", f));
}

std::string fieldList(const pcl::PCLPointCloud2& cloud)
{
  std::string list;
  for (const auto& f : cloud.fields)
    list += (list.empty() ? "" : " ") + f.name;
  return (list.empty() ? std::string("none") : list);
}

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

namespace {

/** Every value of type T at base, base + stride, ... (n of them) is finite. */
template <typename T>
bool allFinite(const std::uint8_t* base, std::size_t n, std::size_t stride)
{
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(readAs<T>(base + i * stride)))
      return (false);
  return (true);
}

} // namespace

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
    if (f->datatype == pcl::PCLPointField::FLOAT32 &&
        !allFinite<float>(base, n, cloud.point_step))
      return (false);
    if (f->datatype == pcl::PCLPointField::FLOAT64 &&
        !allFinite<double>(base, n, cloud.point_step))
      return (false);
  }
  return (true);
}

bool finishLoadedCloud(const std::string& path, pcl::PCLPointCloud2& cloud,
                       std::string* error)
{
  std::string why;
  if (!checkBlobLayout(cloud, why))
    return (fail(error, quoted(path) + ": " + why));
  if (!hasXYZFields(cloud))
    return (fail(error, quoted(path) + ": the cloud has no x/y/z fields (fields: " +
                            fieldList(cloud) + ")"));
  cloud.row_step = cloud.point_step * cloud.width;
  cloud.is_dense = (cloud.is_dense != 0 && allXYZFinite(cloud)) ? 1 : 0;
  return (true);
}

bool readWithPcl(pcl::FileReader& reader, const char* format, const std::string& path,
                 pcl::PCLPointCloud2& cloud, std::string* error)
{
  cloud = pcl::PCLPointCloud2();
  if (reader.read(path, cloud) < 0)
    return (fail(error, quoted(path) + ": PCL's " + format +
                            " reader rejected the file (malformed or truncated data)"));
  return (finishLoadedCloud(path, cloud, error));
}

float readAsFloat(const std::uint8_t* p, std::uint8_t datatype)
{
  switch (datatype) {
  case pcl::PCLPointField::INT8:
    return (readAs<std::int8_t>(p));
  case pcl::PCLPointField::UINT8:
    return (readAs<std::uint8_t>(p));
  case pcl::PCLPointField::INT16:
    return (readAs<std::int16_t>(p));
  case pcl::PCLPointField::UINT16:
    return (readAs<std::uint16_t>(p));
  case pcl::PCLPointField::INT32:
    return (readAs<std::int32_t>(p));
  case pcl::PCLPointField::UINT32:
    return (readAs<std::uint32_t>(p));
  case pcl::PCLPointField::INT64:
    return (readAs<std::int64_t>(p));
  case pcl::PCLPointField::UINT64:
    return (readAs<std::uint64_t>(p));
  case pcl::PCLPointField::FLOAT32:
    return (readAs<float>(p));
  case pcl::PCLPointField::FLOAT64:
    return (readAs<double>(p));
  default:
    return (0.0f);
  }
}

bool hostIsLittleEndian()
{
  const std::uint16_t probe = 1;
  std::uint8_t first;
  std::memcpy(&first, &probe, 1);
  return (first == 1);
}

void swapBytes4(std::uint8_t* data, std::size_t size)
{
  for (std::size_t i = 0; i + 4 <= size; i += 4) {
    std::swap(data[i], data[i + 3]);
    std::swap(data[i + 1], data[i + 2]);
  }
}

} // namespace io_detail
} // namespace phaser
} // namespace pcl
