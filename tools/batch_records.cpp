// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
#include "batch_records.h"
#include "engine_options.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pcl {
namespace phaser {
namespace batch {
namespace {

/** \brief A nested R x C array of numbers as a matrix; false when it is not one. */
template <int R, int C>
bool matrixOf(const Record& value, Eigen::Matrix<double, R, C>& m)
{
  if (!value.is_array() || value.size() != R)
    return false;
  for (int r = 0; r < R; ++r) {
    const Record& row = value[r];
    if (!row.is_array() || row.size() != C)
      return false;
    for (int c = 0; c < C; ++c) {
      if (!row[c].is_number())
        return false;
      m(r, c) = row[c].get<double>();
    }
  }
  return true;
}

Record header(const Pair& pair, std::size_t pairs)
{
  Record r;
  r["pair"] = pair.index;
  r["pairs"] = pairs;
  r["source"] = pair.source;
  r["target"] = pair.target;
  r["source_id"] = pair.source_id;
  r["target_id"] = pair.target_id;
  return r;
}

std::string quaternionText(const Eigen::Matrix3d& R)
{
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0.0)
    q.coeffs() = -q.coeffs();
  char buffer[128];
  std::snprintf(buffer, sizeof(buffer), "%.17g %.17g %.17g %.17g", q.x(), q.y(), q.z(),
                q.w());
  return buffer;
}

std::string positionText(const Eigen::Matrix4d& T)
{
  char buffer[96];
  std::snprintf(buffer, sizeof(buffer), "%.17g %.17g %.17g", T(0, 3), T(1, 3), T(2, 3));
  return buffer;
}

/** \brief Write all of \a text to \a fd. \return false on an error */
bool writeAll(int fd, const std::string& text)
{
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
      return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

/** \brief Whether \a r has every member, of its type, that the tool reads back. */
bool isRecord(const Record& r)
{
  const auto has = [&r](const char* key, Record::value_t type) {
    return r.contains(key) &&
           (r[key].type() == type ||
            (type == Record::value_t::number_integer && r[key].is_number_unsigned()));
  };
  using T = Record::value_t;
  if (!r.is_object() || !has("pair", T::number_unsigned) ||
      !has("pairs", T::number_unsigned) || !has("source", T::string) ||
      !has("target", T::string) || !has("source_id", T::number_integer) ||
      !has("target_id", T::number_integer) || !has("status", T::string) ||
      !has("converged", T::boolean) || r["pair"] >= r["pairs"])
    return false;
  Eigen::Matrix4d T4;
  Eigen::Matrix<double, 6, 6> C;
  return r["status"] != "ok" ||
         (r.contains("transformation") && r.contains("covariance") &&
          matrixOf<4, 4>(r["transformation"], T4) &&
          matrixOf<6, 6>(r["covariance"], C));
}

std::string readWhole(const std::string& path, bool& exists, std::string& error)
{
  std::ifstream in(path, std::ios::binary);
  exists = static_cast<bool>(in);
  if (!in) {
    if (errno != ENOENT)
      error = "cannot read '" + path + "': " + std::strerror(errno);
    return {};
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad())
    error = "cannot read '" + path + "'";
  return text.str();
}

} // namespace

std::string runFingerprint(const PhaserParameters& p, int shard, int shards)
{
  char text[160];
  std::snprintf(text, sizeof(text),
                "shard %d/%d, B %d, grid %d, voxel %.17g, passes %d, %s", shard, shards,
                p.bandwidth, p.spatial_grid_size, p.voxel_size, p.passes,
                centerName(p.projection_center));
  std::string fingerprint = text;
  // The priors, only when set (records written without them keep their fingerprint).
  if (p.region) {
    std::snprintf(text, sizeof(text), ", region %.17g,%.17g,%.17g,%.17g", p.region->x,
                  p.region->y, p.region->z, p.region->radius);
    fingerprint += text;
  }
  if (p.max_tilt_deg > 0.0) {
    std::snprintf(text, sizeof(text), ", tilt %.17g", p.max_tilt_deg);
    fingerprint += text;
  }
  // The fields above are the format of the first records, kept so that they resume;
  // every other row of kParameterRanges that changes results follows, when it is not
  // at its default.
  static const std::set<std::string> head = {
      "bandwidth",         "spatial_grid_size", "voxel_size", "passes",
      "projection_center", "region_x",          "region_y",   "region_z",
      "region_radius",     "max_tilt_deg"};
  const PhaserParameters d;
  for (const ParameterRange& r : kParameterRanges)
    if (r.changes_results && !head.count(r.name) && r.value(p) != r.value(d))
      fingerprint +=
          ", " + std::string(r.name) + " " + parameterText(r, r.value(p), 17);
  return fingerprint;
}

std::string pairKey(const std::string& source, const std::string& target)
{
  return source + '\n' + target;
}

Record alignedRecord(const Pair& pair, std::size_t pairs, const PhaserResult& result,
                     double time_ms)
{
  if (!result.error.empty())
    return failedRecord(pair, pairs, result.error);
  Record r = header(pair, pairs);
  r["status"] = "ok";
  JsonFields set{r};
  set("transformation", result.transformation);
  set("converged", result.converged);
  visitResultFields(result, set);
  r["time_ms"] = time_ms;
  return r;
}

Record failedRecord(const Pair& pair, std::size_t pairs, const std::string& reason)
{
  Record r = header(pair, pairs);
  r["status"] = "failed";
  r["converged"] = false;
  r["error"] = reason;
  return r;
}

std::string readRecords(const std::string& path, std::vector<Record>& records,
                        bool repair)
{
  records.clear();
  bool exists = false;
  std::string error;
  const std::string text = readWhole(path, exists, error);
  if (!error.empty() || !exists)
    return error;
  std::size_t start = 0;
  for (int line = 1; start < text.size(); ++line) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string::npos) { // cut short by a kill: that pair is redone
      if (!repair || text.compare(start, 8, "{\"pair\":") != 0)
        return "'" + path + "' line " + std::to_string(line) + " is cut short";
      if (::truncate(path.c_str(), static_cast<off_t>(start)) != 0)
        return "cannot repair '" + path + "': " + std::strerror(errno);
      break;
    }
    const std::string body = text.substr(start, end - start);
    start = end + 1;
    if (body.find_first_not_of(" \t\r") == std::string::npos)
      continue;
    Record r = Record::parse(body, nullptr, false);
    if (!isRecord(r))
      return "'" + path + "' line " + std::to_string(line) + " is not a pair record";
    records.push_back(std::move(r));
  }
  return {};
}

std::string RecordWriter::open(const std::string& path)
{
  path_ = path;
  fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    return "cannot write '" + path + "': " + std::strerror(errno);
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0)
    return "cannot write '" + path + "': another process is writing it";
  return {};
}

std::string RecordWriter::append(const Record& record)
{
  const off_t before = ::lseek(fd_, 0, SEEK_END);
  if (!writeAll(fd_, record.dump() + "\n")) {
    const std::string reason = std::strerror(errno);
    if (before >= 0 && ::ftruncate(fd_, before) != 0) // leave no torn line behind
      return "cannot write '" + path_ + "': " + reason + ", nor cut the torn line off";
    return "cannot write '" + path_ + "': " + reason;
  }
  if (::fdatasync(fd_) != 0 && errno != EINVAL)
    return "cannot sync '" + path_ + "': " + std::strerror(errno);
  return {};
}

RecordWriter::~RecordWriter()
{
  if (fd_ >= 0)
    ::close(fd_);
}

Eigen::Matrix<double, 6, 6>
g2oInformation(const Eigen::Matrix4d& T, const Eigen::Matrix<double, 6, 6>& covariance)
{
  const Eigen::Matrix3d Rt = T.topLeftCorner<3, 3>().transpose();
  Eigen::Matrix<double, 6, 6> J = Eigen::Matrix<double, 6, 6>::Zero();
  J.topRightCorner<3, 3>() = Rt;         // translation error <- nu
  J.bottomLeftCorner<3, 3>() = 0.5 * Rt; // quaternion x y z <- omega / 2
  const Eigen::Matrix<double, 6, 6> c = J * covariance * J.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(
      0.5 * (c + c.transpose()));
  if (eig.info() != Eigen::Success || !(eig.eigenvalues().minCoeff() > 0.0))
    return Eigen::Matrix<double, 6, 6>::Zero();
  return eig.eigenvectors() * eig.eigenvalues().cwiseInverse().asDiagonal() *
         eig.eigenvectors().transpose();
}

bool convergedEdge(const Record& record, Eigen::Matrix4d& T,
                   Eigen::Matrix<double, 6, 6>& covariance)
{
  return record.value("status", "") == "ok" && record.value("converged", false) &&
         matrixOf<4, 4>(record["transformation"], T) &&
         matrixOf<6, 6>(record["covariance"], covariance);
}

std::string g2oEdge(const Record& record)
{
  Eigen::Matrix4d T;
  Eigen::Matrix<double, 6, 6> covariance;
  if (!convergedEdge(record, T, covariance))
    return {};
  const Eigen::Matrix<double, 6, 6> info = g2oInformation(T, covariance);
  if (info.isZero(0.0))
    return {};
  std::string line = "EDGE_SE3:QUAT " + std::to_string(record["target_id"].get<int>()) +
                     " " + std::to_string(record["source_id"].get<int>()) + " " +
                     positionText(T) + " " + quaternionText(T.topLeftCorner<3, 3>());
  char buffer[32];
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j) {
      std::snprintf(buffer, sizeof(buffer), " %.17g", info(i, j));
      line += buffer;
    }
  return line;
}

std::string g2oVertex(int id, const Eigen::Matrix4d& pose)
{
  return "VERTEX_SE3:QUAT " + std::to_string(id) + " " + positionText(pose) + " " +
         quaternionText(pose.topLeftCorner<3, 3>());
}

std::string writeFileAtomically(const std::string& path, const std::string& text)
{
  const std::string temporary = path + ".tmp." + std::to_string(::getpid());
  const int fd =
      ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0)
    return "cannot write '" + temporary + "': " + std::strerror(errno);
  const bool ok = writeAll(fd, text) && ::fsync(fd) == 0;
  ::close(fd);
  if (!ok || ::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(temporary.c_str());
    return "cannot write '" + path + "': " + reason;
  }
  return {};
}

std::string g2oOdometryEdge(int i, const Eigen::Matrix4d& from,
                            const Eigen::Matrix4d& to, const OdometrySigma& sigma)
{
  const Eigen::Matrix4d T = from.inverse() * to;
  const double rotation = sigma.rotation_deg * M_PI / 180.0;
  Eigen::Matrix<double, 6, 1> diagonal;
  diagonal << Eigen::Vector3d::Constant(1.0 / (sigma.translation * sigma.translation)),
      Eigen::Vector3d::Constant(4.0 / (rotation * rotation));
  std::string line = "EDGE_SE3:QUAT " + std::to_string(i) + " " +
                     std::to_string(i + 1) + " " + positionText(T) + " " +
                     quaternionText(T.topLeftCorner<3, 3>());
  char buffer[32];
  for (int r = 0; r < 6; ++r)
    for (int c = r; c < 6; ++c) {
      std::snprintf(buffer, sizeof(buffer), " %.17g", r == c ? diagonal[r] : 0.0);
      line += buffer;
    }
  return line;
}

std::string g2oGraph(const std::vector<Record>& records,
                     const std::vector<Eigen::Matrix4d>& poses,
                     const std::optional<OdometrySigma>& odometry)
{
  std::string out;
  for (std::size_t id = 0; id < poses.size(); ++id)
    out += g2oVertex(static_cast<int>(id), poses[id]) + "\n";
  // By pair, then by text: an odometry edge and a loop edge of the same pair (--min-gap
  // 1) are both kept, in the order a merge of shards gives them too.
  std::map<std::pair<int, int>, std::set<std::string>> edges;
  if (odometry && !poses.empty()) {
    out += "FIX 0\n";
    for (std::size_t i = 0; i + 1 < poses.size(); ++i)
      edges[{static_cast<int>(i), static_cast<int>(i + 1)}].insert(
          g2oOdometryEdge(static_cast<int>(i), poses[i], poses[i + 1], *odometry));
  }
  for (const Record& r : records)
    if (std::string edge = g2oEdge(r); !edge.empty())
      edges[{r["target_id"].get<int>(), r["source_id"].get<int>()}].insert(
          std::move(edge));
  for (const auto& [ids, lines] : edges)
    for (const std::string& line : lines)
      out += line + "\n";
  return out;
}

} // namespace batch
} // namespace phaser
} // namespace pcl
