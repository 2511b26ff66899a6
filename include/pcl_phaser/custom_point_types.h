/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

/** \file
 *  Opt-in (slow to compile) header: makes pcl::PhaserRegistration usable for any
 *  registered point type with x, y, z beyond those libpcl_phaser instantiates
 *  (PointXYZ, PointXYZI, PointXYZRGB, PointXYZRGBA, PointNormal, PointXYZINormal).
 */

#include <pcl_phaser/impl/phaser_registration.hpp>
#include <pcl_phaser/phaser_registration.h>

#include <pcl/impl/pcl_base.hpp>
#include <pcl/kdtree/impl/kdtree_flann.hpp>
#include <pcl/search/impl/kdtree.hpp>
#include <pcl/search/impl/search.hpp>
