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

/** \brief Each channel mapped robustly to a common scale (normalizeChannel: median
 *  removed, divided by the scaled MAD, clamped), so raw uint16 reflectivity cannot
 * drown meters of range. Per cloud. \throws InvalidArgument if a size differs from \a
 * n. */
ChannelValues normalizeChannels(const ChannelValues& channels, Eigen::Index n);

/** \brief The fused spherical spectrum of a cloud: range (|p|) and every channel binned
 *  on the sphere about the points' origin (shared cell lookup), one SHT each, fused by
 *  the Laplacian pyramid over spherical degree (fuseSpherical). With no channels it is
 *  the range spectrum.
 *  \param[in] points 3 x n, relative to the projection center
 *  \param[in] channels normalized channel values (may be empty)
 *  \param[in] bandwidth B
 *  \param[in] levels pyramid levels
 *  \param[in] num_threads worker threads
 *  \param[out] observed_cells cells with at least one point
 *  \param[out] sampling_ms, sht_ms time spent binning and transforming
 *  \param[out] support when given, the support of the signal for the normalized
 *  refinement (refineRotation): the observed cells and the energy of the signal on
 *  them (the squared de-meaned range, or with channels the squared fused function;
 *  two or three more transforms) */
SphericalSpectrum cloudSphericalSpectrum(const Eigen::Matrix3Xd& points,
                                         const ChannelValues& channels, int bandwidth,
                                         int levels, int num_threads,
                                         int& observed_cells, double& sampling_ms,
                                         double& sht_ms,
                                         SphericalSupport* support = nullptr);

} // namespace pcl::phaser
