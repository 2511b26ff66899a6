// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
// mergeParts(): shard outputs joined into one file, loudly refusing gaps and repeats.
#include "batch_records.h"
#include "text_lines.h"

#include <cerrno>
#include <cstring>
#include <map>
#include <set>
#include <sstream>
#include <unistd.h>

namespace pcl {
namespace phaser {
namespace batch {
namespace {

bool endsWith(const std::string& text, const std::string& suffix)
{
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string mergeRecords(const std::string& out, const std::vector<std::string>& parts)
{
  std::map<std::size_t, std::pair<Record, std::string>> by_index;
  std::size_t pairs = 0;
  for (const std::string& part : parts) {
    std::vector<Record> records;
    if (::access(part.c_str(), R_OK) != 0)
      return "cannot read '" + part + "': " + std::strerror(errno);
    if (std::string error = readRecords(part, records, false); !error.empty())
      return error;
    for (Record& r : records) {
      const std::size_t index = r["pair"].get<std::size_t>();
      const std::size_t total = r.value("pairs", std::size_t{0});
      if (pairs != 0 && total != pairs)
        return "'" + part + "' comes from another list (" + std::to_string(total) +
               " pairs, not " + std::to_string(pairs) + ")";
      pairs = total;
      if (index >= total)
        return "'" + part + "' holds pair " + std::to_string(index) + " of " +
               std::to_string(total);
      const auto [it, fresh] = by_index.emplace(index, std::make_pair(r, part));
      if (!fresh)
        return "pair " + std::to_string(index) + " is in '" + it->second.second +
               "' and in '" + part + "'";
    }
  }
  if (by_index.size() != pairs) { // every index is below pairs: some are missing
    std::size_t first = 0;
    for (const auto& entry : by_index)
      if (entry.first == first)
        ++first;
    return std::to_string(pairs - by_index.size()) + " of " + std::to_string(pairs) +
           " pairs are missing (the first: pair " + std::to_string(first) +
           "); rerun the shards that hold them";
  }
  std::string text;
  for (const auto& [index, entry] : by_index)
    text += entry.first.dump() + "\n";
  return writeFileAtomically(out, text);
}

std::string mergeGraphs(const std::string& out, const std::vector<std::string>& parts)
{
  std::map<int, std::string> vertices;
  std::map<std::pair<int, int>, std::set<std::string>> edges;
  std::set<int> fixed;
  for (const std::string& part : parts) {
    const std::string error = forEachLine(part, [&](const std::string& line, int) {
      std::istringstream fields(line);
      std::string tag;
      int a = -1, b = -1;
      fields >> tag;
      if (tag == "VERTEX_SE3:QUAT" && fields >> a) {
        const auto [it, fresh] = vertices.emplace(a, line);
        if (!fresh && it->second != line)
          return "vertex " + std::to_string(a) + " differs from another part's";
      } else if (tag == "EDGE_SE3:QUAT" && fields >> a >> b) {
        // Odometry edges come with every part, the same (kept once); a loop edge comes
        // with the one part that holds its pair (beside the odometry edge of the pair
        // with --min-gap 1). A third line for a pair means parts of different runs.
        std::set<std::string>& lines = edges[{a, b}];
        lines.insert(line);
        if (lines.size() > 2)
          return "edge " + std::to_string(a) + " " + std::to_string(b) +
                 " differs between parts";
      } else if (tag == "FIX" && fields >> a) {
        fixed.insert(a);
      } else
        return std::string("not a VERTEX_SE3:QUAT, FIX or EDGE_SE3:QUAT line");
      return std::string();
    });
    if (!error.empty())
      return error;
  }
  std::string text;
  for (const auto& [id, line] : vertices)
    text += line + "\n";
  for (const int id : fixed)
    text += "FIX " + std::to_string(id) + "\n";
  for (const auto& [ids, lines] : edges)
    for (const std::string& line : lines)
      text += line + "\n";
  return writeFileAtomically(out, text);
}

} // namespace

std::string mergeParts(const std::string& out, const std::vector<std::string>& parts)
{
  if (parts.empty())
    return "no parts to merge";
  const bool graph = endsWith(out, ".g2o");
  for (const std::string& part : parts)
    if (endsWith(part, ".g2o") != graph)
      return "'" + part + "' is not of the kind of '" + out +
             "' (merge .jsonl parts into a .jsonl file, .g2o parts into a .g2o file)";
  return graph ? mergeGraphs(out, parts) : mergeRecords(out, parts);
}

} // namespace batch
} // namespace phaser
} // namespace pcl
