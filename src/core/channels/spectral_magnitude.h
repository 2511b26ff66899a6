/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "so3/so3_correlation_grid.h"
#include "spatial/spatial_correlation.h"
#include "sphere/spherical_harmonics.h"

#include <vector>

namespace pcl::phaser {

/** \brief The log-magnitude of an occupancy spectrum on shells of equal spatial
 *  frequency, one spherical spectrum per shell. The magnitude of a Fourier transform
 *  does not change when the cloud moves and turns with it (the Fourier-Mellin idea of
 *  Bülow and Birk, "Scale-free registration in 3D", Autonomous Robots 2018), so its
 *  correlation on SO(3) needs no projection center: two partial views of an object,
 *  whose centers never agree, still correlate at their relative rotation. */
struct MagnitudeShells {
  std::vector<SphericalSpectrum> shells; ///< one per frequency, B x B each
  double norm = 0.0;                     ///< sqrt of the summed squared norms
};

/** \brief The MagnitudeShells of \a spectrum (an occupancy half-spectrum) at
 *  \a bandwidth B (2B x 2B directions per shell, trilinear in the spectrum). Each shell
 *  is standardized on the sphere (zero mean, unit variance), so every frequency weighs
 *  alike. \throws InvalidArgument on a bandwidth outside 1..256 or an empty spectrum.
 */
MagnitudeShells magnitudeShells(const SpatialSpectrum& spectrum, int bandwidth);

/** \brief The sum over shells of the SO(3) correlations of \a target and \a source
 *  (same shell count and bandwidth): p_target = R p_source at the peak.
 *  \throws InvalidArgument when the shells do not match. */
So3CorrelationGrid correlateShells(const MagnitudeShells& target,
                                   const MagnitudeShells& source, int num_threads = 1);

} // namespace pcl::phaser
