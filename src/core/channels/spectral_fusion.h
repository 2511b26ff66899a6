/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "sphere/spherical_harmonics.h"

#include <Eigen/Core>

#include <vector>

namespace pcl::phaser {

/** \brief Fusion of K spherical channel spectra (range, intensity, reflectivity, ...)
 * of ONE cloud into a single spectrum, so that one SO(3) correlation serves all
 * channels (PHASER paper, section IV-D). The translation search correlates occupancy
 * only (doc/method.md), so only spherical spectra are fused.
 *
 *  The paper fuses with a Laplacian pyramid: the top-level low-pass is averaged across
 *  channels, every other level keeps the coefficients of the channel with the highest
 *  local energy. A Laplacian pyramid built in the frequency domain with ideal
 *  (brick-wall) filters is exactly a partition of the spectrum into nested bands: the
 *  low-pass of level k keeps the frequencies below f_max / 2^(k+1), its Laplacian is
 * the complement inside level k, decimation only crops the spectrum (it does not change
 * the kept values, apart from a constant scale that cancels on reconstruction), and
 *  reconstruction sums the levels back. Applying the rules level by level is therefore
 *  the same as applying them band by band on the full spectrum, which is what is done
 *  here, without building the pyramid.
 *
 *  Unlike the reference implementation (doc: reference-implementation-notes.md section
 *  6), the bands follow the true frequency structure, not a flattened memory layout:
 *  spherical degree l (rotation-invariant). With L levels the bands are
 *  band 0 = [0, f_max / 2^(L-1)) (averaged) and band b = [f_max / 2^(L-b), f_max /
 *  2^(L-b-1)) for b = 1..L-1 (per-channel selection); the last band is open above.
 *
 *  Target and source are fused independently by the same rule: the selection of a
 *  cloud depends only on that cloud's channels. Channels should be normalized first
 *  (normalizeChannel), otherwise the channel with the largest numeric scale wins every
 *  selection. A channel whose spectrum is exactly zero (a field the cloud lacks, or a
 *  constant one after normalizeChannel) is left out: it would never win a selection but
 *  would scale the averaged band down against the others.
 *
 *  Limit of the rule (paper's, kept): "highest energy" cannot tell structure from
 *  noise within one cloud; leave out channels known to carry no geometry. */
struct FusionParameters {
  /** \brief Pyramid levels L >= 1 (1 = plain average of all channels). */
  int levels = 5;
  /** \brief Half-width, in degrees, of the window over which the per-degree energy of a
   *  spherical channel is summed before the channels are compared (0 = each degree on
   *  its own). Summing a few degrees steadies the choice, so target and source pick the
   *  same channel more often, while staying rotation-invariant. */
  int degree_radius = 1;
};

/** \brief Band of spherical degree \a degree at bandwidth \a bandwidth: 0 for degree <
 *  B / 2^(L-1), else b such that B / 2^(L-b) <= degree < B / 2^(L-b-1), so L-1 for
 *  degree >= B / 2. Exact integer arithmetic.
 *  \param[in] degree l, 0 <= l < B
 *  \param[in] bandwidth B >= 1
 *  \param[in] levels L >= 1
 *  \throws InvalidArgument for arguments outside these ranges */
int sphericalBand(int degree, int bandwidth, int levels);

/** \brief Energy of each degree of a real function's spectrum, |F(l,0)|^2 + 2
 *  sum_{m>=1} |F(l,m)|^2 (the L2 norm of its degree-l component). A rotation mixes the
 *  orders of a degree by a unitary Wigner matrix, so this is rotation-invariant; the
 *  same sum without the factor 2 for the mirrored orders would not be. */
std::vector<double> sphericalDegreeEnergy(const SphericalSpectrum& F);

/** \brief The spherical fusion's choice per degree l: -1 where the degree lies in band
 * 0 (averaged), else the index (into \a channels) of the channel whose windowed degree
 *  energy is largest (ties: lowest index; all-zero channels are skipped).
 *  \throws InvalidArgument as fuseSpherical */
std::vector<int> selectSphericalChannels(const std::vector<SphericalSpectrum>& channels,
                                         const FusionParameters& parameters = {});

/** \brief Fuses spherical channel spectra: degrees of band 0 take the mean of the
 *  channels, every other degree takes the whole row F(l, .) of the channel chosen by
 *  selectSphericalChannels.
 *
 *  The choice is made per degree, never per coefficient (l, m): the energy of a single
 *  order changes when the function rotates, so a per-coefficient rule would pick
 *  different channels for a target and its rotated copy and fuse two different
 *  functions. Per degree the rule commutes with rotations: fuse(rotated channels)
 * equals the rotated fusion, so the SO(3) correlation of fused spectra still peaks at
 * the true rotation. The output is the spectrum of a real function (F(l,0) stays real).
 *  \param[in] channels K >= 1 spectra of equal size B x B (B >= 1)
 *  \param[in] parameters levels and energy window
 *  \throws InvalidArgument for no channels, mismatched or non-square sizes, levels <
 *  1 or degree_radius < 0 */
SphericalSpectrum fuseSpherical(const std::vector<SphericalSpectrum>& channels,
                                const FusionParameters& parameters = {});

/** \brief Robust per-cloud normalization of one channel before its transform, so that
 *  channels of very different numeric scale (uint16 reflectivity, ranges in meters,
 *  intensities in [0, 1]) compete fairly in the fusion.
 *
 *  Returns (v - median) / s clamped to [-clamp, clamp], with s = 1.4826 MAD (the
 *  standard deviation for Gaussian data). When more than half of the values are equal
 *  (MAD = 0, e.g. a mostly-zero reflectivity channel), s falls back to 1.2533 times the
 *  mean absolute deviation from the median (again the standard deviation for Gaussian
 *  data). A constant channel (both zero) maps to zeros. Non-finite values map to 0, the
 *  median: they carry no information and must not reach an FFT; the statistics use the
 *  finite values only. Deterministic (selection on a copy, no sorting of the input).
 *  \param[in] values one value per point
 *  \param[in] clamp outlier limit in robust standard deviations, > 0
 *  \throws InvalidArgument if clamp <= 0 or is not finite */
Eigen::VectorXd normalizeChannel(const Eigen::VectorXd& values, double clamp = 3.0);

} // namespace pcl::phaser
