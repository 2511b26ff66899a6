/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <limits>
#include <memory>

namespace pcl::phaser {

/** \brief ZYZ Euler angles: R = Rz(alpha) Ry(beta) Rz(gamma), beta in [0, pi]. */
struct EulerZYZ {
  double alpha = 0.0;
  double beta = 0.0;
  double gamma = 0.0;
};

/** \brief Rz(alpha) Ry(beta) Rz(gamma), active right-handed rotations. */
Eigen::Matrix3d rotationFromEuler(const EulerZYZ& e);

/** \brief Inverse of rotationFromEuler with beta in [0, pi]; gamma = 0 at the poles. */
EulerZYZ eulerFromRotation(const Eigen::Matrix3d& R);

/** \brief A sample of the (2Bo)^3 Euler grid, flat index (j * N + a) * N + c, N = 2 Bo.
 */
struct So3GridIndex {
  int beta = 0;
  int alpha = 0;
  int gamma = 0;
};

/** \brief alpha = pi a / Bo, beta = pi (2j+1) / (4 Bo), gamma = pi c / Bo. */
EulerZYZ gridEuler(const So3GridIndex& index, int output_bandwidth);

/** \brief Geodesic angle between two rotations, in radians. */
double rotationDistance(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B);

/** \brief C(R) = int f(w) h(R^-1 w) dw (f target, h source) on the (2Bo)^3 Euler grid.
 */
class So3CorrelationGrid {
public:
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

  /** \brief Grid sample with the largest C (ties: lowest flat index, for any
   *  \a num_threads). On a grid of limited tilt only rows whose beta neighbors were
   *  computed take part, so the 3 x 3 x 3 block around the result is sampled. */
  So3GridIndex argmax(int num_threads = 1) const;

  /** \brief Grid sample with the largest C within \a radius radians of the identity
   *  (ties: lowest flat index), or the one nearest the identity when none is. */
  So3GridIndex argmaxNearIdentity(double radius) const;

  /** \brief Rows computed (size() unless limited in tilt). */
  int betaRows() const { return beta_rows_; }

  /** \brief Adds \a other sample by sample (a sum of correlations).
   *  \throws InvalidArgument unless both have the same size and rows. */
  void accumulate(const So3CorrelationGrid& other);

private:
  friend class So3Correlator;
  int output_bandwidth_ = 0;
  int beta_rows_ = 0;
  std::size_t row_stride_ = 0; // 2 (Bo + 1): in-place c2r rows are padded
  struct FftwFree { // bufferRelease, out of line: FFTW stays private to the engine
    std::size_t bytes; // value-initialized (0) with no buffer
    void operator()(double* p) const;
  };
  std::unique_ptr<double[], FftwFree> data_; // beta_rows_ * N * row_stride_ doubles
};

/** \brief Beta rows of the (2Bo)^3 grid holding every rotation of tilt (Euler beta) up
 *  to \a max_tilt radians, plus one for their neighborhoods; at most 2 Bo. */
int betaRowsForTilt(int output_bandwidth, double max_tilt);

} // namespace pcl::phaser
