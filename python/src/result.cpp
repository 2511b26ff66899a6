/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * numpy out: pcl_phaser.Result and what it holds (Verification, Hypothesis,
 * StageTimes, Diagnostics), read-only; matrices are numpy arrays.
 */
#include "field_properties.h"

#include <Eigen/Geometry>

#include <cstdio>

namespace pcl::phaser::python {

namespace {

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0)
{
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer), pattern, a, b, c);
  return buffer;
}

double rotationDeg(const Eigen::Matrix4d& T)
{
  return Eigen::AngleAxisd(Eigen::Matrix3d(T.topLeftCorner<3, 3>())).angle() * 180.0 /
         M_PI;
}

std::string reprOf(const PhaserResult& r)
{
  if (!r.error.empty())
    return "Result(error=" + std::string(py::repr(py::str(r.error))) + ")";
  const PhaserDiagnostics& d = r.diagnostics;
  const Eigen::Vector3d t = r.transformation.topRightCorner<3, 1>();
  return std::string("Result(converged=") + (r.converged ? "True" : "False") +
         format(", rotation %.3f deg", rotationDeg(r.transformation)) +
         format(", translation [%.4f, %.4f, %.4f] m,\n", t.x(), t.y(), t.z()) +
         format("       inlier_fraction %.3f, free_space_violation %.4f / %.4f,",
                d.verification.inlier_fraction, d.verification.free_space_violation,
                d.verification.reverse_free_space_violation) +
         format(" constraint %.3f, rank %.3f,\n", d.verification.constraint,
                d.verification.rank) +
         format("       %.0f hypotheses (chosen %.0f), %.1f ms)",
                static_cast<double>(d.hypotheses.size()), r.chosen_hypothesis,
                d.times.total());
}

void bindParts(py::module_& m)
{
  py::class_<Verification> verification(m, "Verification",
                                        "How a pose verifies; shares in [0, 1].");
  bindFieldProperties(verification,
                      [](auto& v, auto&& f) { visitVerificationFields(v, f); });
  verification // the short names of verification_score and verification_rank
      .def_readonly("score", &Verification::score)
      .def_readonly("rank", &Verification::rank)
      .def("__repr__", [](const Verification& v) {
        return format("Verification(inlier_fraction=%.4f, score=%.4f, ",
                      v.inlier_fraction, v.score) +
               format("free_space_violation=%.4f, reverse_free_space_violation=%.4f, ",
                      v.free_space_violation, v.reverse_free_space_violation) +
               format("constraint=%.4f, rank=%.4f)", v.constraint, v.rank);
      });
  py::class_<Hypothesis> hypothesis(m, "Hypothesis",
                                    "A verified hypothesis of the global search.");
  bindFieldProperties(hypothesis,
                      [](auto& h, auto&& f) { visitHypothesisFields(h, f); });
  hypothesis.def_readonly("verification", &Hypothesis::verification)
      .def("__repr__", [](const Hypothesis& h) {
        return format("Hypothesis(rotation %.3f deg, rank %.4f, from_orientation=",
                      rotationDeg(h.transformation), h.verification.rank) +
               (h.from_orientation ? "True)" : "False)");
      });
  py::class_<StageTimes> times(m, "StageTimes", "Milliseconds spent in each stage.");
  bindFieldProperties(times, [](auto& t, auto&& f) { visitStageTimes(t, f); });
  times.def_property_readonly("total", &StageTimes::total)
      .def("__repr__", [](const StageTimes& t) {
        return format("StageTimes(total %.1f ms, target %.1f ms)", t.total(), t.target);
      });
}

void bindDiagnostics(py::module_& m)
{
  using D = PhaserDiagnostics;
  py::class_<D> diagnostics(m, "Diagnostics",
                            "What one align measured on the way to its answer: the "
                            "fields of the tools' JSON, and the lists behind them.");
  bindFieldProperties(diagnostics,
                      [](auto& d, auto&& f) { visitDiagnosticsFields(d, f); });
  diagnostics.def_readonly("verification", &D::verification)
      .def_readonly("hypotheses", &D::hypotheses)
      .def_readonly("rotation_samples", &D::rotation_samples)
      .def_readonly("rotation_weights", &D::rotation_weights)
      .def_readonly("times", &D::times);
}

} // namespace

void bindResult(py::module_& m)
{
  bindParts(m);
  bindDiagnostics(m);
  using R = PhaserResult;
  py::class_<R> result(
      m, "Result",
      "What one align found: transformation (T_target_source, p_target = "
      "T p_source), converged, covariance (6 x 6, rotation vector then "
      "translation), every field of the tools' JSON under its key "
      "(verification_rank, stages_ms, hypotheses, ...); error: why it "
      "was refused ('' on success).");
  bindFieldProperties(result, [](auto& r, auto&& f) { visitResultState(r, f); });
  result.def_readonly("diagnostics", &R::diagnostics)
      .def_property_readonly("verification",
                             [](const R& r) { return r.diagnostics.verification; })
      .def_property_readonly("times", [](const R& r) { return r.diagnostics.times; })
      .def("__repr__", &reprOf)
      .def("to_dict", &resultState,
           "Every field as a dict, named as in pcl_phaser_align --json and the batch's "
           "records (the verification's flat: verification_rank, ...; stages_ms).")
      .def(py::pickle(&resultState, &resultFromState));
}

} // namespace pcl::phaser::python
