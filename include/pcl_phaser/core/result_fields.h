/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
/** \file result_fields.h
 * \brief The one list of a PhaserResult's fields and their names, written by
 * `pcl_phaser_align --json`, the records of `pcl_phaser_batch` and the Python Result
 * (to_dict() and its pickled state). Header only: no PCL, no JSON library.
 *
 * A visitor is called as visitor(name, field) with each field, a reference (const when
 * the result is): double, int, bool, std::string, ProjectionCenter, an Eigen matrix or
 * vector, a std::vector, or a FieldGroup / FieldList of nested fields. Writers read
 * the fields; a reader (the Python state) visits a mutable result and assigns them.
 */
#pragma once

#include <pcl_phaser/core/result.h>

namespace pcl::phaser {

/** \brief Fields nested under one name ("stages_ms"): visit(visitor) visits them. */
template <class Visit>
struct FieldGroup {
  Visit visit;
};

/** \brief A list under one name ("hypotheses"): visit(items[i], visitor) visits the
 *  fields of one item. \tparam Items a reference to a [const] std::vector */
template <class Items, class Visit>
struct FieldList {
  Items items;
  Visit visit;
};

/** \brief A [const] Verification's fields, score and rank as "verification_*". */
template <class T, class Visitor>
void visitVerificationFields(T& v, Visitor&& visitor)
{
  visitor("inlier_fraction", v.inlier_fraction);
  visitor("verification_score", v.score);
  visitor("free_space_violation", v.free_space_violation);
  visitor("reverse_free_space_violation", v.reverse_free_space_violation);
  visitor("constraint", v.constraint);
  visitor("verification_rank", v.rank);
}

/** \brief A [const] StageTimes' milliseconds, by its members' names. */
template <class T, class Visitor>
void visitStageTimes(T& t, Visitor&& visitor)
{
  visitor("target", t.target);
  visitor("sampling", t.sampling);
  visitor("sht", t.sht);
  visitor("so3", t.so3);
  visitor("refinement", t.refinement);
  visitor("translation", t.translation);
  visitor("orientation", t.orientation);
  visitor("verification", t.verification);
}

/** \brief The figures of a [const] PhaserResult that every writer writes (the tools
 *  after their "transformation" and "converged"); runner_up_rank -infinity: none. */
template <class R, class Visitor>
void visitResultFields(R& r, Visitor&& visitor)
{
  auto& d = r.diagnostics;
  visitor("covariance", r.covariance);
  visitor("rotation_score", d.rotation_score);
  visitor("translation_score", d.translation_score);
  visitor("normalized_overlap", d.normalized_overlap);
  visitVerificationFields(d.verification, visitor);
  visitor("runner_up_rank", d.runner_up_rank);
  visitor("runner_up_error", d.runner_up_error);
  visitor("verification_radius", d.verification_radius);
  visitor("verification_samples", d.verification_samples);
  visitor("verified", d.verified);
  visitor("refusal", d.refusal);
  visitor("passes", d.passes);
  const auto times = [&t = d.times](auto&& v) { visitStageTimes(t, v); };
  visitor("stages_ms", FieldGroup<decltype(times)>{times});
}

/** \brief Every field of a [const] PhaserResult, what restores it exactly: those of
 *  visitResultFields() and the rest; a hypothesis by its members' names. */
template <class R, class Visitor>
void visitResultState(R& r, Visitor&& visitor)
{
  visitor("error", r.error);
  visitor("transformation", r.transformation);
  visitor("converged", r.converged);
  visitor("projection_center", r.projection_center);
  visitor("chosen_hypothesis", r.chosen_hypothesis);
  visitor("lever_arm", r.lever_arm);
  visitor("translation_covariance", r.translation_covariance);
  visitor("fit_covariance", r.fit_covariance);
  visitResultFields(r, visitor);
  const auto each = [](auto& h, auto&& v) {
    v("transformation", h.transformation), v("rotation", h.rotation);
    v("translation", h.translation), v("rotation_score", h.rotation_score);
    v("overlap", h.overlap), v("from_orientation", h.from_orientation);
    visitVerificationFields(h.verification, v);
  };
  auto& hypotheses = r.diagnostics.hypotheses;
  visitor("hypotheses",
          FieldList<decltype(hypotheses), decltype(each)>{hypotheses, each});
  visitor("rotation_samples", r.diagnostics.rotation_samples);
  visitor("rotation_weights", r.diagnostics.rotation_weights);
}

} // namespace pcl::phaser
