// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file pcl_phaser_align_steps.h
 * \brief The quiet steps of `pcl_phaser_align`: build the finite typed cloud that is
 * registered from a PCLPointCloud2, move a blob in place so that every field of the
 * input file survives in the -o output, and measure the errors against a known
 * transform. The ICP refinement: pcl_phaser_align_icp.h.
 */
#pragma once

#include <pcl/PCLPointCloud2.h>
#include <pcl/common/io.h>
#include <pcl/filters/filter.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>

namespace pcl {
namespace phaser {
namespace align_tool {

/** \brief Whether a field exists and is float32 or float64 (count 1 or more). */
inline bool isFloatField(const pcl::PCLPointCloud2& blob, int index)
{
  return (index >= 0 && blob.fields[index].count >= 1 &&
          (blob.fields[index].datatype == pcl::PCLPointField::FLOAT32 ||
           blob.fields[index].datatype == pcl::PCLPointField::FLOAT64));
}

template <typename T>
double readAs(const std::uint8_t* p)
{
  T v;
  std::memcpy(&v, p, sizeof(v));
  return (static_cast<double>(v));
}

/** \brief One scalar of any PCL datatype as a double (NaN for an unknown type). */
inline double readScalar(const std::uint8_t* p, std::uint8_t type)
{
  using F = pcl::PCLPointField;
  switch (type) {
  case F::INT8:
    return (readAs<std::int8_t>(p));
  case F::UINT8:
    return (readAs<std::uint8_t>(p));
  case F::INT16:
    return (readAs<std::int16_t>(p));
  case F::UINT16:
    return (readAs<std::uint16_t>(p));
  case F::INT32:
    return (readAs<std::int32_t>(p));
  case F::UINT32:
    return (readAs<std::uint32_t>(p));
  case F::INT64:
    return (readAs<std::int64_t>(p));
  case F::UINT64:
    return (readAs<std::uint64_t>(p));
  case F::FLOAT32:
    return (readAs<float>(p));
  case F::FLOAT64:
    return (readAs<double>(p));
  default:
    return (std::numeric_limits<double>::quiet_NaN());
  }
}

/** \brief The points of a blob with finite x/y/z as PointXYZ or PointXYZI (intensity
 * of any numeric type converted to float; 0 when the blob has none).
 * \param[in] blob a self-consistent cloud whose x, y, z are float32 or float64 */
template <typename PointT>
typename pcl::PointCloud<PointT>::Ptr toFiniteCloud(const pcl::PCLPointCloud2& blob)
{
  auto cloud = pcl::make_shared<pcl::PointCloud<PointT>>();
  const int ix = pcl::getFieldIndex(blob, "x"), iy = pcl::getFieldIndex(blob, "y");
  const int iz = pcl::getFieldIndex(blob, "z"),
            ii = pcl::getFieldIndex(blob, "intensity");
  const std::size_t n = static_cast<std::size_t>(blob.width) * blob.height;
  cloud->resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint8_t* p = blob.data.data() + k * blob.point_step;
    const auto field = [&](int i) {
      return (readScalar(p + blob.fields[i].offset, blob.fields[i].datatype));
    };
    PointT& q = (*cloud)[k];
    q.x = static_cast<float>(field(ix));
    q.y = static_cast<float>(field(iy));
    q.z = static_cast<float>(field(iz));
    if constexpr (pcl::traits::has_intensity_v<PointT>)
      q.intensity = ii < 0 ? 0.0f : static_cast<float>(field(ii));
  }
  cloud->is_dense = false;
  pcl::Indices kept;
  pcl::removeNaNFromPointCloud(*cloud, *cloud, kept);
  return (cloud);
}

/** \brief Apply a rigid transform to a blob in place: x/y/z are moved and, when present
 * as floating-point fields, normal_x/y/z rotated; every other field is left as it is,
 * and non-finite points stay non-finite. */
inline void transformBlob(pcl::PCLPointCloud2& blob, const Eigen::Matrix4d& T)
{
  if (blob.point_step == 0)
    return;
  for (const std::string prefix : {"", "normal_"}) {
    const int idx[3] = {pcl::getFieldIndex(blob, prefix + "x"),
                        pcl::getFieldIndex(blob, prefix + "y"),
                        pcl::getFieldIndex(blob, prefix + "z")};
    if (!std::all_of(idx, idx + 3, [&](int i) { return (isFloatField(blob, i)); }))
      continue;
    const double shift = prefix.empty() ? 1.0 : 0.0; // directions only rotate
    for (std::size_t k = 0; k < blob.data.size() / blob.point_step; ++k) {
      std::uint8_t* p = blob.data.data() + k * blob.point_step;
      Eigen::Vector3d v;
      for (int a = 0; a < 3; ++a)
        v[a] = readScalar(p + blob.fields[idx[a]].offset, blob.fields[idx[a]].datatype);
      v = T.topLeftCorner<3, 3>() * v + shift * T.topRightCorner<3, 1>();
      for (int a = 0; a < 3; ++a) {
        const pcl::PCLPointField& f = blob.fields[idx[a]];
        const float single = static_cast<float>(v[a]);
        if (f.datatype == pcl::PCLPointField::FLOAT32)
          std::memcpy(p + f.offset, &single, sizeof(single));
        else
          std::memcpy(p + f.offset, &v[a], sizeof(double));
      }
    }
  }
}

/** \brief What one stage (PHASER or ICP) found, and its errors when the truth is known
 * (NaN otherwise). */
struct Stage {
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();
  bool ran = false, converged = false;
  double time_ms = 0.0;
  double rre_deg = std::numeric_limits<double>::quiet_NaN(); ///< rotation error, deg
  double rte_m = std::numeric_limits<double>::quiet_NaN();   ///< translation error, m
};

/** \brief Set the rotation error (degrees, the geodesic angle of R_truth^T R) and the
 * translation error (meters, |t - t_truth|) of a stage. */
inline void computeErrors(Stage& s, const Eigen::Matrix4d& truth)
{
  const Eigen::Matrix3d dR =
      truth.topLeftCorner<3, 3>().transpose() * s.transform.topLeftCorner<3, 3>();
  const Eigen::Vector3d axis(dR(2, 1) - dR(1, 2), dR(0, 2) - dR(2, 0),
                             dR(1, 0) - dR(0, 1));
  s.rre_deg = std::atan2(0.5 * axis.norm(), 0.5 * (dR.trace() - 1.0)) * 180.0 /
              3.14159265358979323846;
  s.rte_m = (s.transform.topRightCorner<3, 1>() - truth.topRightCorner<3, 1>()).norm();
}

} // namespace align_tool
} // namespace phaser
} // namespace pcl
