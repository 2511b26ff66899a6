// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
#include "batch_pairs.h"
#include "engine_options.h"
#include "text_lines.h"

#include <Eigen/LU>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>

namespace pcl {
namespace phaser {
namespace batch {
namespace {

/** \brief A finite number, or nothing. */
std::optional<double> number(const std::string& text)
{
  double v = 0.0;
  errno = 0;
  if (!parseNumber(text, v) || errno == ERANGE)
    return std::nullopt;
  return v;
}

/** \brief Whether \a text is valid UTF-8 (records are JSON, which needs it). */
bool isUtf8(const std::string& text)
{
  try {
    (void)nlohmann::json(text).dump();
    return true;
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

/** \brief Whether the top left of \a m is a rotation (R^T R = I, det R = 1, to 1e-4).
 */
bool isRigid(const Eigen::Matrix4d& m)
{
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <
             1e-4 &&
         R.determinant() > 0.0;
}

/** \brief A row-major 3x4 from 12 tokens starting at \a first, or nothing. */
std::optional<Eigen::Matrix4d> rigid3x4(const std::vector<std::string>& t,
                                        std::size_t first)
{
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  for (int k = 0; k < 12; ++k) {
    const std::optional<double> v = number(t[first + k]);
    if (!v)
      return std::nullopt;
    m(k / 4, k % 4) = *v;
  }
  return m;
}

int idOf(const std::string& name, PairList& list, std::map<std::string, int>& ids)
{
  const auto [it, added] = ids.emplace(name, static_cast<int>(list.names.size()));
  if (added)
    list.names.push_back(name);
  return it->second;
}

} // namespace

std::string folderOf(const std::string& file)
{
  const std::size_t slash = file.rfind('/');
  if (slash == std::string::npos)
    return ".";
  return slash == 0 ? "/" : file.substr(0, slash);
}

std::string resolvePath(const std::string& folder, const std::string& path)
{
  if (path.empty() || path[0] == '/' || folder == ".")
    return path;
  return folder + (folder.back() == '/' ? "" : "/") + path;
}

std::string readPairList(const std::string& path, PairList& list)
{
  list = PairList{};
  const std::string folder = folderOf(path);
  std::map<std::string, int> ids;
  std::map<std::pair<std::string, std::string>, int> seen;
  return forEachLine(path, [&](const std::string& text, int line) {
    const std::vector<std::string> t = lineFields(text);
    if (t.size() != 2 && t.size() != 14)
      return "expected SOURCE TARGET [12 numbers], got " + std::to_string(t.size()) +
             " fields";
    if (!isUtf8(t[0]) || !isUtf8(t[1]))
      return std::string("a path is not valid UTF-8");
    Pair p;
    p.index = list.pairs.size();
    p.source = t[0];
    p.target = t[1];
    if (t.size() == 14) {
      const std::optional<Eigen::Matrix4d> guess = rigid3x4(t, 2);
      if (!guess)
        return std::string("the guess is not 12 finite numbers");
      if (!isRigid(*guess))
        return std::string("the guess is not a rigid transformation");
      p.guess = *guess;
      p.has_guess = true;
    }
    const auto [it, fresh] = seen.emplace(std::make_pair(p.source, p.target), line);
    if (!fresh)
      return "repeats the pair of line " + std::to_string(it->second);
    p.source_path = resolvePath(folder, p.source);
    p.target_path = resolvePath(folder, p.target);
    p.source_id = idOf(p.source, list, ids);
    p.target_id = idOf(p.target, list, ids);
    list.pairs.push_back(std::move(p));
    return std::string();
  });
}

std::string readScanList(const std::string& path, std::vector<std::string>& given,
                         std::vector<std::string>& resolved)
{
  given.clear();
  resolved.clear();
  return forEachLine(path, [&](const std::string& text, int) {
    const std::vector<std::string> t = lineFields(text);
    if (t.size() != 1)
      return std::string("expected one path per line");
    if (!isUtf8(t[0]))
      return std::string("the path is not valid UTF-8");
    if (std::find(given.begin(), given.end(), t[0]) != given.end())
      return "'" + t[0] + "' is listed twice";
    given.push_back(t[0]);
    resolved.push_back(resolvePath(folderOf(path), t[0]));
    return std::string();
  });
}

std::string readPoses(const std::string& path, std::vector<Eigen::Matrix4d>& poses)
{
  poses.clear();
  return forEachLine(path, [&](const std::string& text, int) {
    const std::vector<std::string> t = lineFields(text);
    const std::optional<Eigen::Matrix4d> pose =
        t.size() < 12 ? std::nullopt : rigid3x4(t, t.size() - 12);
    if (!pose)
      return std::string("expected a row-major 3x4 pose (12 numbers)");
    poses.push_back(*pose);
    return std::string();
  });
}

std::string readTrajectory(const std::string& scans, const std::string& poses_path,
                           std::vector<std::string>& given,
                           std::vector<std::string>& resolved,
                           std::vector<Eigen::Matrix4d>& poses)
{
  std::string error = readScanList(scans, given, resolved);
  if (error.empty())
    error = readPoses(poses_path, poses);
  if (error.empty() && poses.size() != given.size())
    error = "'" + poses_path + "' holds " + std::to_string(poses.size()) +
            " poses for the " + std::to_string(given.size()) + " scans of '" + scans +
            "'";
  return error;
}

PairList makeCandidates(const std::vector<std::string>& given,
                        const std::vector<std::string>& resolved,
                        const std::vector<Eigen::Matrix4d>& poses, double radius,
                        int min_gap)
{
  PairList list;
  list.names = given;
  list.poses = poses;
  const int n = static_cast<int>(std::min(given.size(), poses.size()));
  for (int i = 0; i < n; ++i)
    for (int j = i + std::max(min_gap, 1); j < n; ++j) {
      const double d =
          (poses[i].topRightCorner<3, 1>() - poses[j].topRightCorner<3, 1>()).norm();
      if (!(d <= radius))
        continue;
      Pair p;
      p.index = list.pairs.size();
      p.source = given[j];
      p.target = given[i];
      p.source_path = resolved[j];
      p.target_path = resolved[i];
      p.source_id = j;
      p.target_id = i;
      list.pairs.push_back(std::move(p));
    }
  return list;
}

std::string formatPairList(const PairList& list)
{
  std::string out = "# source target [T_target_source guess, row-major 3x4]\n";
  char buffer[64];
  for (const Pair& p : list.pairs) {
    out += p.source + " " + p.target;
    for (int k = 0; p.has_guess && k < 12; ++k) {
      std::snprintf(buffer, sizeof(buffer), " %.17g", p.guess(k / 4, k % 4));
      out += buffer;
    }
    out += "\n";
  }
  return out;
}

std::optional<std::pair<int, int>> parseShard(const std::string& text)
{
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos)
    return std::nullopt;
  const std::optional<double> k = number(text.substr(0, slash));
  const std::optional<double> n = number(text.substr(slash + 1));
  if (!k || !n || *k != std::floor(*k) || *n != std::floor(*n) || *k < 0 || *n < 1 ||
      *k >= *n || *n > 1e6)
    return std::nullopt;
  return std::make_pair(static_cast<int>(*k), static_cast<int>(*n));
}

std::vector<std::size_t> shardPairs(const PairList& list, int k, int n)
{
  // Target groups in order of first appearance, list order inside each.
  std::vector<std::vector<std::size_t>> groups;
  std::map<int, std::size_t> group_of;
  for (const Pair& p : list.pairs) {
    const auto [it, fresh] = group_of.emplace(p.target_id, groups.size());
    if (fresh)
      groups.emplace_back();
    groups[it->second].push_back(p.index);
  }
  // Cut groups larger than an even share, then deal the pieces, largest first, to
  // the shard with the fewest pairs (ties: the lower shard, the earlier piece).
  const std::size_t share = std::max<std::size_t>(
      1, (list.pairs.size() + static_cast<std::size_t>(n) - 1) / n);
  std::vector<std::vector<std::size_t>> pieces;
  for (const std::vector<std::size_t>& g : groups)
    for (std::size_t first = 0; first < g.size(); first += share)
      pieces.emplace_back(g.begin() + first,
                          g.begin() + std::min(g.size(), first + share));
  std::vector<std::size_t> order(pieces.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return pieces[a].size() > pieces[b].size();
  });
  std::vector<std::size_t> load(n, 0);
  std::vector<int> owner(pieces.size(), 0);
  for (const std::size_t piece : order) {
    const int s =
        static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
    owner[piece] = s;
    load[s] += pieces[piece].size();
  }
  std::vector<std::size_t> mine;
  for (std::size_t piece = 0; piece < pieces.size(); ++piece)
    if (owner[piece] == k)
      mine.insert(mine.end(), pieces[piece].begin(), pieces[piece].end());
  return mine;
}

} // namespace batch
} // namespace phaser
} // namespace pcl
