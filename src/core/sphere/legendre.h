/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <vector>

namespace pcl::phaser {

/** \brief Orthonormal associated Legendre functions with the Condon-Shortley phase,
 *  Pbar_l^m(x), so that Y_l^m = Pbar_l^m(cos theta) e^{i m phi} is orthonormal on S^2.
 *
 * Evaluated for 0 <= m <= l < B by the stable log-space start and three-term recurrence
 * of doc/so3-correlation-spec.md section 2 (accurate up to B = 256).
 * \param[in] bandwidth B
 * \param[in] x the argument cos(theta), in [-1, 1]
 * \return values at index legendreIndex(l, m, B)
 */
std::vector<double> normalizedLegendre(int bandwidth, double x);

/** \brief Position of (l, m) in the packed arrays: column-major in m, l = m..B-1. */
inline int legendreIndex(int l, int m, int bandwidth)
{
  // Offset of column m is sum_{k<m} (B - k) = m B - m (m - 1) / 2.
  return m * bandwidth - m * (m - 1) / 2 + (l - m);
}

/** \brief Number of (l, m) pairs with 0 <= m <= l < B. */
inline int legendreCount(int bandwidth)
{
  return bandwidth * (bandwidth + 1) / 2;
}

} // namespace pcl::phaser
