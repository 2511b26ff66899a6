/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <pcl_phaser/core/parameters.h> // Channel

#include <pcl/point_types.h> // has_field, has_intensity, has_color

#include <cstdint>
#include <type_traits>

// Ouster field tags, unknown to PCL: declared so that has_field can test for them.
namespace pcl {
namespace fields {
struct reflectivity;
struct ambient;
} // namespace fields

/** \brief The point channels of pcl::PhaserRegistration. */
namespace phaser {

// The Channel flags (CHANNEL_RANGE, ...): pcl_phaser/core/parameters.h.

/** \brief Which channels a point type carries; specialize it to show or hide fields:
 *  \code
 *  template <> struct pcl::phaser::PointChannels<MyPoint> {
 *    static constexpr bool intensity = false;  // not a return strength in MyPoint
 *    static constexpr bool reflectivity = true, ambient = false, color = false;
 *  };
 *  \endcode
 *  Range always comes from xyz, never from a `range` field (units differ). */
template <typename PointT>
struct PointChannels {
  static constexpr bool intensity = pcl::traits::has_intensity_v<PointT>;
  static constexpr bool reflectivity =
      pcl::traits::has_field<PointT, pcl::fields::reflectivity>::value;
  static constexpr bool ambient =
      pcl::traits::has_field<PointT, pcl::fields::ambient>::value;
  static constexpr bool color = pcl::traits::has_color_v<PointT>;
};

/** \brief The channel flags of \a PointT. */
template <typename PointT>
constexpr std::uint32_t availableChannels()
{
  using C = PointChannels<PointT>;
  return CHANNEL_RANGE | (C::intensity ? CHANNEL_INTENSITY : 0u) |
         (C::reflectivity ? CHANNEL_REFLECTIVITY : 0u) |
         (C::ambient ? CHANNEL_AMBIENT : 0u) | (C::color ? CHANNEL_COLOR : 0u);
}

/** \brief Value of one non-range channel of a point (0 when the type lacks it). */
template <Channel channel, typename PointT>
float channelValue(const PointT& p)
{
  using C = PointChannels<PointT>;
  if constexpr (channel == CHANNEL_INTENSITY && C::intensity)
    return static_cast<float>(p.intensity);
  else if constexpr (channel == CHANNEL_REFLECTIVITY && C::reflectivity)
    return static_cast<float>(p.reflectivity);
  else if constexpr (channel == CHANNEL_AMBIENT && C::ambient)
    return static_cast<float>(p.ambient);
  else if constexpr (channel == CHANNEL_COLOR && C::color)
    return 0.299f * p.r + 0.587f * p.g + 0.114f * p.b; // ITU-R BT.601 luma
  else {
    static_assert(channel != CHANNEL_RANGE, "range comes from xyz");
    return 0.0f;
  }
}

} // namespace phaser
} // namespace pcl
