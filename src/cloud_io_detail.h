/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

// Private to the cloud_io*.cpp files: helpers shared by the PCD, PLY, KITTI and
// transform pieces of <pcl_phaser/cloud_io.h>. Not installed.

#include <pcl/PCLPointCloud2.h>
#include <pcl/PCLPointField.h>
#include <pcl/io/file_io.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace pcl {
namespace phaser {
namespace io_detail {

/** Headers longer than this are rejected (real PCD/PLY headers are a few hundred
 *  bytes; the Stanford bunny PLY, with its obj_info block, is about 700). */
constexpr std::size_t kMaxHeaderBytes = 1u << 20;

/* --------------------------- messages and strings ------------------------------ */

/** Store message in *error (if given) and return false. */
bool fail(std::string* error, const std::string& message);

/** 'path', for messages. */
std::string quoted(const std::string& path);

/** Printable, bounded excerpt of untrusted text for error messages. */
std::string excerpt(const std::string& text, std::size_t max_length = 40);

/** The extension of path, lower-cased (".pcd"), or empty. */
std::string lowerExtension(const std::string& path);

/** "'path': no file extension (expected ...)" or "... unsupported extension ...". */
std::string unsupportedExtensionMessage(const std::string& path);

/** "'path': cannot open for <what> (<strerror(errno)>)"; call right after the failed
 *  open, before errno changes. */
std::string openErrorMessage(const std::string& path, const char* what);

std::vector<std::string> splitWhitespace(const std::string& line);

/** Strict decimal unsigned integer: digits only, no sign, no trailing characters. */
bool parseUnsigned(const std::string& token, std::uint64_t& value);

/** Control characters other than '\t' ('\r' is stripped from line ends). PCL splits
 *  header lines on ' ', '\t' (and '\r'), so any other whitespace would make it see
 *  different tokens than the checks here. */
bool hasControlCharacter(const std::string& text);

/* ------------------------------ saturating math -------------------------------- */

/** a * b, saturating at the largest uint64 instead of wrapping. */
inline std::uint64_t mulSat(std::uint64_t a, std::uint64_t b)
{
  if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a)
    return (std::numeric_limits<std::uint64_t>::max());
  return (a * b);
}

/** a + b, saturating at the largest uint64 instead of wrapping. */
inline std::uint64_t addSat(std::uint64_t a, std::uint64_t b)
{
  if (b > std::numeric_limits<std::uint64_t>::max() - a)
    return (std::numeric_limits<std::uint64_t>::max());
  return (a + b);
}

/* ---------------------------------- files -------------------------------------- */

/** One header line and the byte offset just past its '\n'. */
struct HeaderLine {
  std::string text;
  std::size_t next_offset = 0;
};

/** The next line of a header buffer ('\r' stripped), starting at pos; advances pos
 *  past its '\n'. The last line may lack a '\n'. Returns false at the end. */
bool nextLine(const std::string& buffer, std::size_t& pos, HeaderLine& line);

/** Checks shared by every reader: the path names a readable, non-empty regular
 *  file. Returns its size. */
bool checkInputFile(const std::string& path, std::uintmax_t& size, std::string* error);

/** Read up to max_bytes from the start of a file, or from offset. */
bool readBytes(const std::string& path, std::uintmax_t offset, std::size_t max_bytes,
               std::string& out);

/** The first min(file_size, kMaxHeaderBytes) bytes of a file, where a header is. */
bool readHeaderPrefix(const std::string& path, std::uintmax_t file_size,
                      std::string& prefix, std::string* error);

/** Write size bytes to path (created or truncated). */
bool writeFile(const std::string& path, const void* data, std::size_t size, bool binary,
               std::string* error);

/* ---------------------------------- blobs -------------------------------------- */

bool findField(const pcl::PCLPointCloud2& cloud, const std::string& name,
               const pcl::PCLPointField*& field);

/** The cloud has fields named x, y and z. */
bool hasXYZFields(const pcl::PCLPointCloud2& cloud);

/** The field names separated by spaces, or "none". */
std::string fieldList(const pcl::PCLPointCloud2& cloud);

/** Structural consistency of a blob: known field types inside point_step, and data
 *  holding exactly width * height * point_step bytes. */
bool checkBlobLayout(const pcl::PCLPointCloud2& cloud, std::string& why);

/** Every point has finite x, y and z (float fields; integer coordinates always are). */
bool allXYZFinite(const pcl::PCLPointCloud2& cloud);

/** Validate what a reader produced and normalise row_step / is_dense. */
bool finishLoadedCloud(const std::string& path, pcl::PCLPointCloud2& cloud,
                       std::string* error);

/** Read path with one of PCL's readers (format: "PCD" or "PLY", for the message),
 *  then finishLoadedCloud(). */
bool readWithPcl(pcl::FileReader& reader, const char* format, const std::string& path,
                 pcl::PCLPointCloud2& cloud, std::string* error);

/** A value of type T stored at p (any alignment, host byte order), as float. */
template <typename T>
float readAs(const std::uint8_t* p)
{
  T v;
  std::memcpy(&v, p, sizeof(v));
  return (static_cast<float>(v));
}

/** A field value as float, whatever its stored type (host byte order); 0 for an
 *  unknown type. */
float readAsFloat(const std::uint8_t* p, std::uint8_t datatype);

bool hostIsLittleEndian();

/** Reverse the byte order of each 4-byte word of data (size a multiple of 4). */
void swapBytes4(std::uint8_t* data, std::size_t size);

/* ------------------------------ PLY header model -------------------------------- */

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
std::uint64_t plyTypeSize(const std::string& type);

/** Walk a PLY body up to its range_grid element and check that every range_grid
 *  vertex index is in [0, vertex_count). PCL computes index * point_step in 32 bits,
 *  so a crafted index wraps its bounds check and PCL reads gigabytes out of bounds
 *  (segfault). Ascii bodies must hold one element per line. */
bool checkPlyRangeGridIndices(const std::string& path, const std::string& format,
                              const std::vector<PlyElement>& elements,
                              std::uint64_t data_offset, std::uint64_t vertex_count,
                              std::string& why);

/* -------------------------------- the formats ---------------------------------- */

/** PCD: header check, then PCL's reader. */
bool loadPcd(const std::string& path, std::uintmax_t file_size,
             pcl::PCLPointCloud2& cloud, std::string* error);
/** PCD: binary, fields written in offset order (see cloud_io_pcd.cpp). */
bool savePcd(const std::string& path, const pcl::PCLPointCloud2& cloud,
             std::string* error);

/** PLY: header (and range_grid) check, then PCL's reader. */
bool loadPly(const std::string& path, std::uintmax_t file_size,
             pcl::PCLPointCloud2& cloud, std::string* error);
/** PLY: binary little-endian, vertices only. */
bool savePly(const std::string& path, const pcl::PCLPointCloud2& cloud,
             std::string* error);

/** KITTI .bin: float32 x y z reflectance records. */
bool loadKittiBin(const std::string& path, std::uintmax_t file_size,
                  pcl::PCLPointCloud2& cloud, std::string* error);
bool saveKittiBin(const std::string& path, const pcl::PCLPointCloud2& cloud,
                  std::string* error);

} // namespace io_detail
} // namespace phaser
} // namespace pcl
