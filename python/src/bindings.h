/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The pieces of the Python module pcl_phaser, one concept per file: clouds (numpy in),
 * parameters, result (numpy out, its pickled state), target and align.
 */
#pragma once

#include <pcl_phaser/core/pipeline.h>

#include <cstdint>
#include <memory>
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h> // every unit sees the same type casters
#include <string>

namespace pcl::phaser::python {

namespace py = pybind11;

/** \brief A cloud converted from numpy: finite points and their channel values. */
struct Cloud {
  Eigen::Matrix3Xd points;
  ChannelValues channels;
  bool has_intensity = false; ///< the array had a fourth (intensity) column
};

/** \brief \a array, a float32/float64 numpy array (N, 3) or (N, 4) of any memory
 *  order, as doubles: rows with a non-finite x, y or z are skipped (as PCL's face skips
 *  them); the fourth column becomes the intensity channel when \a use_intensity.
 *  \throws py::type_error not a numpy array, or not float32/float64
 *  \throws py::value_error wrong shape, empty, no finite row, non-finite intensity */
Cloud cloudFromArray(const py::handle& array, const char* which, bool use_intensity);

/** \brief The 4 x 4 \a guess (None: identity) as doubles.
 *  \throws py::type_error not convertible to a float array
 *  \throws py::value_error not 4 x 4, or not finite */
Eigen::Matrix4d guessFromObject(const py::handle& guess);

/** \brief \a params as PhaserParameters: None gives the defaults, a dict its keywords.
 *  \throws py::type_error neither None, a dict nor a pcl_phaser.Parameters */
PhaserParameters parametersFrom(const py::handle& params);

/** \brief Whether \a params fuse the intensity channel (CHANNEL_INTENSITY). */
bool usesIntensity(const PhaserParameters& params);

/** \brief pcl::phaser::align on \a target and \a source with the GIL released. */
PhaserResult alignReleased(const Target& target, const SourceCloud& source,
                           const Eigen::Matrix4d& guess,
                           const PhaserParameters& params);

/** \brief The result's every field as a dict (visitResultState(), bit for bit) and
 *  back, for to_dict() and pickle. \throws py::value_error a field missing or wrong */
py::dict resultState(const PhaserResult& r);
PhaserResult resultFromState(const py::dict& state);

void bindParameters(py::module_& m);
void bindResult(py::module_& m);
void bindTarget(py::module_& m);

} // namespace pcl::phaser::python
