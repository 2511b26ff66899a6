/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include "so3/so3_grid.h"

#include <cstddef>
#include <limits>

namespace pcl::phaser {

/** \brief The correlation C(R) = int f(w) h(R^-1 w) dw sampled on the (2Bo)^3 Euler
 * grid (f = target, h = source). Owns its buffer; cheap to move. */
class So3CorrelationGrid {
public:
  So3CorrelationGrid() = default;
  So3CorrelationGrid(So3CorrelationGrid&&) noexcept;
  So3CorrelationGrid& operator=(So3CorrelationGrid&&) noexcept;
  ~So3CorrelationGrid();

  int outputBandwidth() const { return output_bandwidth_; }
  /** \brief Samples per axis, N = 2 Bo. */
  int size() const { return 2 * output_bandwidth_; }

  /** \brief C(alpha_a, beta_j, gamma_c); -infinity for rows j >= betaRows(). */
  double operator()(int j, int a, int c) const
  {
    if (j >= beta_rows_)
      return -std::numeric_limits<double>::infinity();
    return data_[(static_cast<std::size_t>(j) * size() + a) * row_stride_ + c];
  }
  double operator()(const So3GridIndex& i) const
  {
    return (*this)(i.beta, i.alpha, i.gamma);
  }

  /** \brief Grid sample with the largest C; ties go to the lowest flat index, for any
   *  \a num_threads. On a grid of limited tilt (So3Correlator::correlate with
   *  beta_rows) only the rows whose beta neighbors were computed take part, so the
   *  3 x 3 x 3 block around the result (rotationNeighborhood) is always sampled. */
  So3GridIndex argmax(int num_threads = 1) const;

  /** \brief Grid sample with the largest C among those within \a radius (radians,
   *  geodesic angle) of the identity, ties to the lowest flat index; the sample nearest
   *  the identity when none lies within \a radius. */
  So3GridIndex argmaxNearIdentity(double radius) const;

  /** \brief Beta rows computed: rows j < betaRows() hold C, the others -infinity
   *  (size() unless the correlation was limited in tilt). */
  int betaRows() const { return beta_rows_; }

private:
  friend class So3Correlator;
  int output_bandwidth_ = 0;
  int beta_rows_ = 0;
  std::size_t row_stride_ = 0; // 2 (Bo + 1): in-place c2r rows are padded
  double* data_ = nullptr;     // fftw_malloc'ed, beta_rows_ * N * row_stride_ doubles
};

/** \brief Beta rows of the (2Bo)^3 grid that hold every rotation of tilt (Euler beta,
 *  which is at most the rotation angle) up to \a max_tilt radians, plus one row so the
 *  neighborhood of each such sample is computed too; at most 2 Bo. */
int betaRowsForTilt(int output_bandwidth, double max_tilt);

} // namespace pcl::phaser
