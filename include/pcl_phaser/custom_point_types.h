/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

/** \file
 *  Opt-in header for point types that libpcl_phaser does not instantiate (it ships
 *  PointXYZ, PointXYZI, PointXYZRGB, PointXYZRGBA, PointNormal and PointXYZINormal).
 *  Including it makes pcl::PhaserRegistration<MyPoint, MyPoint> usable for any
 * registered point type with x, y, z, whether or not PCL_NO_PRECOMPILE is defined: it
 * brings the template definitions of PhaserRegistration and of the PCL pieces
 * pcl::Registration needs for a new type (PCLBase, the kd-tree search). Those make
 * every translation unit that includes it much slower to compile, which is why the
 * main header does not include it.
 */

#include <pcl_phaser/impl/phaser_registration.hpp>
#include <pcl_phaser/phaser_registration.h>

#include <pcl/impl/pcl_base.hpp>
#include <pcl/kdtree/impl/kdtree_flann.hpp>
#include <pcl/search/impl/kdtree.hpp>
#include <pcl/search/impl/search.hpp>
