/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * numpy in: clouds (N x 3 or N x 4, float32 or float64, any memory order) and the
 * guess.
 */
#include "bindings.h"

#include <cmath>
#include <pybind11/numpy.h>

namespace pcl::phaser::python {

namespace {

/** \brief The finite rows of \a a (x, y, z finite) as a Cloud. */
template <typename T>
Cloud finiteRows(const py::array& a, const char* which, bool use_intensity)
{
  const auto v = a.unchecked<T, 2>(); // strided: C, Fortran or any view
  const py::ssize_t n = v.shape(0);
  const bool intensity = use_intensity && v.shape(1) == 4;
  Cloud cloud;
  cloud.has_intensity = v.shape(1) == 4;
  cloud.points.resize(3, n);
  Eigen::VectorXd values(intensity ? n : 0);
  Eigen::Index count = 0;
  for (py::ssize_t i = 0; i < n; ++i) {
    const double x = v(i, 0), y = v(i, 1), z = v(i, 2);
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
      continue;
    cloud.points.col(count) = Eigen::Vector3d(x, y, z);
    if (intensity) {
      values[count] = static_cast<double>(v(i, 3));
      if (!std::isfinite(values[count]))
        throw py::value_error(std::string(which) + ": the intensity of row " +
                              std::to_string(i) + " is not finite");
    }
    ++count;
  }
  if (count == 0)
    throw py::value_error(std::string(which) + ": none of its " + std::to_string(n) +
                          " points has a finite x, y and z");
  cloud.points.conservativeResize(3, count);
  if (intensity) {
    values.conservativeResize(count);
    cloud.channels.push_back(std::move(values));
  }
  return cloud;
}

} // namespace

Cloud cloudFromArray(const py::handle& array, const char* which, bool use_intensity)
{
  if (!py::isinstance<py::array>(array))
    throw py::type_error(std::string(which) +
                         " must be a numpy array of shape (N, 3) or (N, 4), not " +
                         std::string(py::str(py::type::of(array).attr("__name__"))));
  const auto a = py::reinterpret_borrow<py::array>(array);
  // Equivalent types: native byte order (">f8" is refused rather than misread).
  const bool is_float = py::array_t<float>::check_(a);
  const bool is_double = py::array_t<double>::check_(a);
  if (!is_float && !is_double)
    throw py::type_error(std::string(which) +
                         " must be float32 or float64 (native byte order), not " +
                         std::string(py::str(a.dtype())));
  if (a.ndim() != 2 || (a.shape(1) != 3 && a.shape(1) != 4))
    throw py::value_error(
        std::string(which) +
        " must have shape (N, 3) (x y z) or (N, 4) (x y z intensity), "
        "not " +
        std::string(py::str(a.attr("shape"))));
  if (a.shape(0) == 0)
    throw py::value_error(std::string(which) + " is empty (0 points)");
  return is_float ? finiteRows<float>(a, which, use_intensity)
                  : finiteRows<double>(a, which, use_intensity);
}

Eigen::Matrix4d guessFromObject(const py::handle& guess)
{
  if (guess.is_none())
    return Eigen::Matrix4d::Identity();
  // ensure() returns a null array, the Python error cleared, when it cannot convert.
  const auto a = py::array_t<double, py::array::forcecast>::ensure(guess);
  if (!a || py::isinstance<py::str>(guess))
    throw py::type_error("guess must be a 4 x 4 array of numbers (or None)");
  if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4)
    throw py::value_error("guess must have shape (4, 4), not " +
                          std::string(py::str(a.attr("shape"))));
  const auto v = a.unchecked<2>();
  Eigen::Matrix4d T;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      T(r, c) = v(r, c);
  if (!T.allFinite())
    throw py::value_error("guess has a non-finite entry");
  return T;
}

} // namespace pcl::phaser::python
