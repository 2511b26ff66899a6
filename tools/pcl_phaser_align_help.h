// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
#pragma once

namespace pcl::phaser::align_tool {

/** \brief Prints pcl_phaser_align's syntax, options (with their defaults and ranges)
 *  and exit codes; \a program: the name it was run as. */
void printHelp(const char* program);

} // namespace pcl::phaser::align_tool
