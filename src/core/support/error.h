/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <stdexcept>
#include <string>

namespace pcl::phaser {

/** \brief Thrown by the engine when a parameter is outside its documented range
 *  (e.g. a bandwidth outside [1, 256]) or inputs have inconsistent sizes.
 *  The PCL adapter catches it and reports it with PCL_ERROR.
 */
class InvalidArgument : public std::invalid_argument {
public:
  using std::invalid_argument::invalid_argument;
};

/** \brief Largest legal spherical bandwidth (input B and output Bo). */
constexpr int kMaxBandwidth = 256;

/** \brief Throws InvalidArgument unless 1 <= bandwidth <= kMaxBandwidth. */
inline void checkBandwidth(int bandwidth, const char* what = "bandwidth")
{
  if (bandwidth < 1 || bandwidth > kMaxBandwidth)
    throw InvalidArgument(std::string(what) + " must be in [1, " +
                          std::to_string(kMaxBandwidth) + "], got " +
                          std::to_string(bandwidth));
}

} // namespace pcl::phaser
