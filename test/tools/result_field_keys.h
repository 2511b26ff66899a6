/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The keys of visitResultFields() that pcl_phaser_align --json, the batch's records and
 * the benchmarks' CSV write, in order: collected from the code, and pinned by the table
 * of doc/cli.md (test ResultKeys.AreTheDocumentedOnes), so that a new or renamed field
 * is documented there.
 */
#pragma once

#include <pcl_phaser/core/result.h>

#include <string>
#include <vector>

namespace pcl::phaser::test {

/** \brief A visitor of visitResultFields() that keeps the names it is given. */
struct FieldNames {
  std::vector<std::string>& names;
  template <class T>
  void operator()(const char* name, const T&)
  {
    names.emplace_back(name);
  }
};

/** \brief The names of visitResultFields()' fields (after transformation and
 *  converged). */
inline std::vector<std::string> resultFieldKeys()
{
  const PhaserResult result;
  std::vector<std::string> names;
  visitResultFields(result, FieldNames{names});
  return names;
}

/** \brief The members of "stages_ms": milliseconds per stage. */
inline std::vector<std::string> stageKeys()
{
  const StageTimes times;
  std::vector<std::string> names;
  visitStageTimes(times, FieldNames{names});
  return names;
}

/** \brief The shared result keys. */
inline const std::vector<std::string> kResultFieldKeys = resultFieldKeys();
inline const std::vector<std::string> kStageKeys = stageKeys();

} // namespace pcl::phaser::test
