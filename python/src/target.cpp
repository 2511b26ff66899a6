/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser.Target (a target prepared once for many sources) and pcl_phaser.align.
 * The clouds are converted with the GIL held; the align itself runs without it.
 */
#include "bindings.h"

#include <pybind11/numpy.h>

namespace pcl::phaser::python {

namespace {

/** A target for Python: the engine's Target and the settings it was made with. */
struct PyTarget {
  std::shared_ptr<const Target> target;
  PhaserParameters params;
  Eigen::VectorXd intensity; ///< the fused intensity channel; empty: none
  bool fused() const { return intensity.size() > 0; }
};

PyTarget targetFrom(Cloud cloud, const PhaserParameters& params)
{
  PyTarget t;
  t.params = params;
  if (!cloud.channels.empty())
    t.intensity = cloud.channels.front();
  t.target = std::make_shared<const Target>(std::move(cloud.points),
                                            std::move(cloud.channels));
  return t;
}

PyTarget makeTarget(const py::handle& points, const py::handle& params)
{
  const PhaserParameters p = parametersFrom(params);
  return targetFrom(cloudFromArray(points, "target", usesIntensity(p)), p);
}

/** The source for \a t: its intensity is fused exactly when the target's is. */
SourceCloud sourceFor(const PyTarget& t, const py::handle& source)
{
  Cloud cloud = cloudFromArray(source, "source", t.fused());
  if (t.fused() && !cloud.has_intensity)
    throw py::value_error("the target fuses intensity and the source has none (N, 3): "
                          "pass both with 4 columns, or make the Target from 3");
  return {std::move(cloud.points), std::move(cloud.channels)};
}

/** \a source against \a t; the target's channels are fixed when it is made. */
PhaserResult alignWith(const PyTarget& t, const py::handle& source,
                       const py::handle& guess, const py::handle& params)
{
  const PhaserParameters p = params.is_none() ? t.params : parametersFrom(params);
  const SourceCloud s = sourceFor(t, source);
  return alignReleased(*t.target, s, guessFromObject(guess), p);
}

/** One align: intensity is fused when the parameters ask for it and both clouds have
 *  it (as pcl::PhaserRegistration fuses the channels both point types carry). */
PhaserResult alignOnce(const py::handle& source, const py::handle& target,
                       const py::handle& guess, const py::handle& params)
{
  if (py::isinstance<PyTarget>(target))
    return alignWith(target.cast<const PyTarget&>(), source, guess, params);
  const PhaserParameters p = parametersFrom(params);
  Cloud s = cloudFromArray(source, "source", usesIntensity(p));
  const PyTarget t =
      targetFrom(cloudFromArray(target, "target", !s.channels.empty()), p);
  if (!t.fused())
    s.channels.clear();
  const Eigen::Matrix4d T = guessFromObject(guess);
  return alignReleased(*t.target, {std::move(s.points), std::move(s.channels)}, T, p);
}

/** The target's points (and intensity) as an (N, 3) or (N, 4) float64 array. */
py::array_t<double> pointsOf(const PyTarget& t)
{
  const Eigen::Matrix3Xd& points = t.target->points();
  const py::ssize_t n = points.cols(), columns = t.fused() ? 4 : 3;
  py::array_t<double> a({n, columns});
  auto v = a.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i) {
    for (py::ssize_t k = 0; k < 3; ++k)
      v(i, k) = points(k, i);
    if (t.fused())
      v(i, 3) = t.intensity[i];
  }
  return a;
}

} // namespace

PhaserResult alignReleased(const Target& target, const SourceCloud& source,
                           const Eigen::Matrix4d& guess, const PhaserParameters& params)
{
  py::gil_scoped_release released;
  return align(target, source, guess, params);
}

void bindTarget(py::module_& m)
{
  py::class_<PyTarget>(m, "Target",
                       "A target prepared once (at its first align) for many sources; "
                       "aligns against it may run in several threads at once.")
      .def(py::init(&makeTarget), py::arg("points"), py::arg("params") = py::none(),
           "points: (N, 3) or (N, 4) float32/float64; params: its default settings")
      .def("align", &alignWith, py::arg("source"), py::arg("guess") = py::none(),
           py::arg("params") = py::none(),
           "Registers source (N, 3) or (N, 4) against this target; guess: 4 x 4 "
           "T_target_source to start from. Returns a Result.")
      .def_property_readonly("params", [](const PyTarget& t) { return t.params; })
      .def_property_readonly("points", &pointsOf, "(N, 3) or (N, 4) float64 copy")
      .def("__len__", [](const PyTarget& t) { return t.target->points().cols(); })
      .def("__repr__",
           [](const PyTarget& t) {
             return "Target(" + std::to_string(t.target->points().cols()) + " points" +
                    (t.fused() ? ", intensity)" : ")");
           })
      .def(py::pickle(
          [](const PyTarget& t) { return py::make_tuple(pointsOf(t), t.params); },
          [](const py::tuple& state) { return makeTarget(state[0], state[1]); }));
  m.def(
      "align", &alignOnce, py::arg("source"), py::arg("target"),
      py::arg("guess") = py::none(), py::arg("params") = py::none(),
      "Registers source against target (numpy (N, 3) x y z or (N, 4) x y z intensity, "
      "float32/float64, or a Target); guess: 4 x 4 T_target_source (None: identity); "
      "params: Parameters, a dict or None. Returns a Result; bad input raises "
      "ValueError / TypeError.");
}

} // namespace pcl::phaser::python
