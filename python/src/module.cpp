/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The extension module pcl_phaser._pcl_phaser; the package pcl_phaser re-exports it.
 */
#include "bindings.h"

#include <pcl_phaser/core/warm_up.h>

PYBIND11_MODULE(_pcl_phaser, m)
{
  namespace py = pybind11;
  using namespace pcl::phaser::python;
  m.doc() = "PHASER global point-cloud registration (the pcl_phaser engine) on numpy "
            "arrays.";
  bindParameters(m);
  bindResult(m);
  bindTarget(m);
  m.def(
      "warm_up",
      [](const py::handle& params, int points) {
        const pcl::phaser::PhaserParameters p = parametersFrom(params);
        pcl::phaser::WarmUpOptions options;
        options.points = points;
        std::string problem;
        {
          py::gil_scoped_release released;
          problem = pcl::phaser::warmUp(p, options);
        }
        if (!problem.empty())
          throw py::value_error(problem);
      },
      py::arg("params") = py::none(), py::arg("points") = 120000,
      "Does once what the first align of a process would do first (transforms, "
      "plans, threads); later aligns return bit for bit the same.");
}
