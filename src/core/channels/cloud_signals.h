/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "so3/so3_refinement.h"
#include "spatial/spatial_correlation.h"
#include "sphere/spherical_harmonics.h"

#include <pcl_phaser/core/types.h>

#include <Eigen/Core>

#include <vector>

namespace pcl::phaser {

/** \brief normalizeChannel of each channel. \throws InvalidArgument if a channel's
 *  size differs from \a n. */
ChannelValues normalizeChannels(const ChannelValues& channels, Eigen::Index n);

/** \brief The fused spherical spectrum of a cloud (3 x n, relative to the projection
 *  center): range |p| and every normalized channel binned on the sphere, transformed
 *  and fused over \a levels (fuseSpherical); the range spectrum without channels.
 *  \param[out] observed_cells cells with at least one point
 *  \param[out] sampling_ms, sht_ms time added for binning and transforming
 *  \param[out] support if given, for refineRotation: the observed cells and the squared
 *  correlated signal (range, or the fused function) on them */
SphericalSpectrum cloudSphericalSpectrum(const Eigen::Matrix3Xd& points,
                                         const ChannelValues& channels, int bandwidth,
                                         int levels, int num_threads,
                                         int& observed_cells, double& sampling_ms,
                                         double& sht_ms,
                                         SphericalSupport* support = nullptr);

} // namespace pcl::phaser
