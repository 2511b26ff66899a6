/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "sphere/spherical_harmonics.h"

#include <Eigen/Core>

#include <vector>

namespace pcl::phaser {

/** \brief Fusion of K spherical channel spectra (range, intensity, ...) of one cloud
 *  into one spectrum, so that one SO(3) correlation serves all channels (PHASER paper,
 *  IV-D). The paper's Laplacian pyramid with ideal filters is a partition of the
 *  spectrum into nested bands, so its rules are applied band by band on spherical
 *  degree l (rotation-invariant): band 0 = [0, B / 2^(L-1)) takes the mean of the
 *  channels, band b = [B / 2^(L-b), B / 2^(L-b-1)) for b = 1..L-1 the channel of
 *  highest energy. Each cloud is fused on its own; normalize the channels first
 *  (normalizeChannel). All-zero channels are left out (they would scale the mean
 *  down). */
struct FusionParameters {
  /** \brief Pyramid levels L >= 1 (1 = plain average of all channels). */
  int levels = 5;
  /** \brief Half-width, in degrees, of the window of degree energies summed before the
   *  channels are compared (0 = each degree alone): steadies the choice, so target and
   *  source pick the same channel more often. */
  int degree_radius = 1;
};

/** \brief Band of spherical \a degree (0 <= l < B) at \a bandwidth B with \a levels L:
 *  0 for l < B / 2^(L-1), else b with B / 2^(L-b) <= l < B / 2^(L-b-1), in exact
 * integer arithmetic. \throws InvalidArgument for arguments outside these ranges */
int sphericalBand(int degree, int bandwidth, int levels);

/** \brief The fusion's choice per degree l: -1 in band 0 (averaged), else the index of
 *  the channel of largest windowed degree energy |F(l,0)|^2 + 2 sum_{m>=1} |F(l,m)|^2
 *  (ties: lowest index; all-zero channels skipped). \throws InvalidArgument as
 *  fuseSpherical */
std::vector<int> selectSphericalChannels(const std::vector<SphericalSpectrum>& channels,
                                         const FusionParameters& parameters = {});

/** \brief Fuses spherical channel spectra: band-0 degrees take the mean of the
 *  channels, every other degree the whole row F(l, .) of the channel
 *  selectSphericalChannels picks. Chosen per degree, never per (l, m), so fusion
 *  commutes with rotations and the correlation of fused spectra still peaks at the
 *  true rotation.
 *  \param[in] channels K >= 1 spectra of equal size B x B
 *  \throws InvalidArgument for no channels, mismatched or non-square sizes, levels < 1
 *  or degree_radius < 0 */
SphericalSpectrum fuseSpherical(const std::vector<SphericalSpectrum>& channels,
                                const FusionParameters& parameters = {});

/** \brief Robust per-cloud normalization of one channel, so channels of very different
 *  scale compete fairly in the fusion: (v - median) / s clamped to [-clamp, clamp],
 *  s = 1.4826 MAD, or 1.2533 x the mean absolute deviation when the MAD is 0 (both the
 *  standard deviation for Gaussian data). A constant channel maps to zeros, non-finite
 *  values to 0; the statistics use the finite values. Deterministic.
 *  \param[in] clamp outlier limit in robust standard deviations, > 0
 *  \throws InvalidArgument if clamp <= 0 or is not finite */
Eigen::VectorXd normalizeChannel(const Eigen::VectorXd& values, double clamp = 3.0);

} // namespace pcl::phaser
