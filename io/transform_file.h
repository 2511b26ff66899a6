/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
/** \file transform_file.h
 * \brief The T_target_source text format of --gt (tools, bench/ and tests). */
#pragma once

#include <Eigen/Core>

#include <string>

namespace pcl {
namespace phaser {

/** \brief Parse a rigid transform from text: 16 numbers (row-major 4x4) or 12 numbers
 * (row-major 3x4, the last row is then 0 0 0 1), separated by whitespace; '#' starts a
 * comment that runs to the end of the line. The rotation block must be orthonormal
 * (max |R^T R - I| <= tolerance) with det > 0, and a given last row must be 0 0 0 1
 * within tolerance. The numbers are returned unchanged (no re-orthonormalization).
 * \param[in] text the numbers
 * \param[out] transform the parsed transform (unchanged on failure)
 * \param[out] error if not null, receives a human-readable reason on failure
 * \param[in] tolerance the orthonormality tolerance, finite and >= 0 (default 1e-4)
 * \return true on success
 */
bool parseTransform(const std::string& text, Eigen::Matrix4d& transform,
                    std::string* error = nullptr, double tolerance = 1e-4);

/** \brief Load a rigid transform from a text file of at most 1 MiB (format and checks
 * as in parseTransform()), e.g. the T_*.txt and relative.txt files of the shared data.
 * \param[in] path the file to read
 * \param[out] transform the loaded transform (unchanged on failure)
 * \param[out] error if not null, receives a human-readable reason on failure
 * \param[in] tolerance the orthonormality tolerance, finite and >= 0 (default 1e-4)
 * \return true on success
 */
bool loadTransform(const std::string& path, Eigen::Matrix4d& transform,
                   std::string* error = nullptr, double tolerance = 1e-4);

} // namespace phaser
} // namespace pcl
