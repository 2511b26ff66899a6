/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
// KITTI Velodyne .bin scans: little-endian float32 records x y z reflectance.
#include "cloud_io_detail.h"

#include <fstream>
#include <string>
#include <vector>

namespace pcl {
namespace phaser {
namespace io_detail {
namespace {

/** Bytes of one KITTI record: four float32. */
constexpr std::uintmax_t kRecord = 16;

pcl::PCLPointField makeFloatField(const std::string& name, std::uint32_t offset)
{
  pcl::PCLPointField field;
  field.name = name;
  field.offset = offset;
  field.datatype = pcl::PCLPointField::FLOAT32;
  field.count = 1;
  return (field);
}

} // namespace

bool loadKittiBin(const std::string& path, std::uintmax_t file_size,
                  pcl::PCLPointCloud2& cloud, std::string* error)
{
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
    swapBytes4(cloud.data.data(), cloud.data.size());
  cloud.is_dense = allXYZFinite(cloud) ? 1 : 0;
  return (true);
}

bool saveKittiBin(const std::string& path, const pcl::PCLPointCloud2& cloud,
                  std::string* error)
{
  // x, y, z (present: saveCloud checked) and intensity (0 when absent).
  const pcl::PCLPointField* fields[4] = {nullptr, nullptr, nullptr, nullptr};
  const char* names[4] = {"x", "y", "z", "intensity"};
  for (int k = 0; k < 4; ++k)
    findField(cloud, names[k], fields[k]);
  const std::size_t n = static_cast<std::size_t>(cloud.width) * cloud.height;
  std::vector<float> out(4 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* point = cloud.data.data() + i * cloud.point_step;
    for (int k = 0; k < 4; ++k) {
      const pcl::PCLPointField* f = fields[k];
      out[4 * i + k] = f ? readAsFloat(point + f->offset, f->datatype) : 0.0f;
    }
  }
  const std::size_t bytes = out.size() * sizeof(float);
  if (!hostIsLittleEndian())
    swapBytes4(reinterpret_cast<std::uint8_t*>(out.data()), bytes);
  return (writeFile(path, out.data(), bytes, true, error));
}

} // namespace io_detail
} // namespace phaser
} // namespace pcl
