/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_bench loop-closure: judges the records of `pcl_phaser_batch --scans ...`
 * against the reference poses of the trajectory: per pair the reference distance and
 * overlap, the pose error and its NEES under the record's covariance; then the accepted
 * candidates, the wrong accepted edges and the covariance's calibration.
 */
#include "batch_pairs.h"
#include "batch_records.h"
#include "cloud_reading.h"
#include "statistics.h"
#include "subcommands.h"

#include <pcl/filters/filter.h>
#include <pcl/kdtree/kdtree_flann.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace batch = pcl::phaser::batch;
using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using pcl::phaser::median;

namespace {

// A revisit is right within 5 deg / 0.6 m (doc/benchmarks.md's revisit criterion).
const double kRightDeg = 5.0, kRightM = 0.6;
// 95 % quantiles of chi-square with 6 and 3 degrees of freedom.
const double kChi6 = 12.592, kChi3 = 7.815;

struct Row {
  std::size_t pair = 0;
  std::string source, target;
  double distance = 0, overlap = 0, rre = NAN, rte = NAN;
  double nees = NAN, nees_rot = NAN, nees_trans = NAN, sigma_rot_deg = NAN,
         sigma_trans_m = NAN;
  bool ok = false, converged = false;
};

Cloud::Ptr load(const std::string& path, std::map<std::string, Cloud::Ptr>& cache)
{
  Cloud::Ptr& cloud = cache[path];
  if (!cloud) {
    cloud.reset(new Cloud);
    std::string error;
    if (!pcl::phaser::loadCloud(path, *cloud, &error))
      std::fprintf(stderr, "%s\n", error.c_str());
    pcl::Indices kept;
    cloud->is_dense = false;
    pcl::removeNaNFromPointCloud(*cloud, *cloud, kept);
  }
  return cloud;
}

/** \brief Share of about 2000 source points within 0.3 m of the target under \a T
 *  (the overlap proxy of pairs.txt). */
double overlap(const Cloud& source, const Cloud::Ptr& target, const Eigen::Matrix4d& T)
{
  if (source.empty() || target->empty())
    return 0.0;
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(target);
  const std::size_t step = std::max<std::size_t>(1, source.size() / 2000);
  std::size_t near = 0, n = 0;
  pcl::Indices index(1);
  std::vector<float> d2(1);
  for (std::size_t i = 0; i < source.size(); i += step, ++n) {
    const Eigen::Vector3d p = (T * source[i].getVector4fMap().cast<double>()).head<3>();
    pcl::PointXYZ q(float(p.x()), float(p.y()), float(p.z()));
    near += tree.nearestKSearch(q, 1, index, d2) == 1 && d2[0] <= 0.09f;
  }
  return double(near) / double(n);
}

/** \brief Errors and NEES of a record against the reference \a truth. */
void judge(const batch::Record& r, const Eigen::Matrix4d& truth, Row& row)
{
  Eigen::Matrix4d T;
  Matrix6d C;
  for (int i = 0; i < 16; ++i)
    T(i / 4, i % 4) = r["transformation"][i / 4][i % 4].get<double>();
  for (int i = 0; i < 36; ++i)
    C(i / 6, i % 6) = r["covariance"][i / 6][i % 6].get<double>();
  const Eigen::Matrix3d dR =
      truth.topLeftCorner<3, 3>() * T.topLeftCorner<3, 3>().transpose();
  const Eigen::AngleAxisd aa(dR);
  Vector6d e;
  e << aa.angle() * aa.axis(), truth.topRightCorner<3, 1>() - T.topRightCorner<3, 1>();
  row.rre = aa.angle() * 180.0 / M_PI;
  row.rte = e.tail<3>().norm();
  if (!row.converged)
    return;
  row.nees = e.dot(C.ldlt().solve(e));
  row.nees_rot = e.head<3>().dot(C.topLeftCorner<3, 3>().ldlt().solve(e.head<3>()));
  row.nees_trans =
      e.tail<3>().dot(C.bottomRightCorner<3, 3>().ldlt().solve(e.tail<3>()));
  row.sigma_rot_deg = std::sqrt(C.topLeftCorner<3, 3>().trace() / 3.0) * 180.0 / M_PI;
  row.sigma_trans_m = std::sqrt(C.bottomRightCorner<3, 3>().trace() / 3.0);
}

void summarize(const std::vector<Row>& rows, double real_overlap)
{
  std::size_t failed = 0, accepted = 0, right = 0, wrong = 0, real = 0,
              real_accepted = 0;
  std::size_t in6 = 0, in_rot = 0, in_trans = 0;
  double nees_sum = 0;
  std::vector<double> rre, rte;
  for (const Row& w : rows) {
    failed += !w.ok;
    const bool is_right = w.rre <= kRightDeg && w.rte <= kRightM;
    real += w.overlap >= real_overlap;
    real_accepted += w.overlap >= real_overlap && w.converged;
    if (!w.converged)
      continue;
    ++accepted;
    (is_right ? right : wrong)++;
    rre.push_back(w.rre);
    rte.push_back(w.rte);
    nees_sum += w.nees;
    in6 += w.nees <= kChi6;
    in_rot += w.nees_rot <= kChi3;
    in_trans += w.nees_trans <= kChi3;
  }
  const auto maximum = [](const std::vector<double>& v) {
    return v.empty() ? std::numeric_limits<double>::quiet_NaN()
                     : *std::max_element(v.begin(), v.end());
  };
  const double n = std::max<double>(1, accepted);
  std::printf(
      "| candidates | failed | accepted | right / wrong accepted | overlap >= %.2f "
      "| of those accepted | RRE median / max (deg) | RTE median / max (m) |\n"
      "|---|---|---|---|---|---|---|---|\n"
      "| %zu | %zu | %zu | %zu / %zu | %zu | %zu (%.1f %%) | %.3f / %.3f | %.3f / "
      "%.3f |\n\n",
      real_overlap, rows.size(), failed, accepted, right, wrong, real, real_accepted,
      100.0 * real_accepted / std::max<double>(1, real), median(rre), maximum(rre),
      median(rte), maximum(rte));
  std::printf(
      "| accepted | inside 95 %% (6-D) | rotation (3-D) | translation (3-D) | mean "
      "NEES (6 = consistent) |\n|---|---|---|---|---|\n"
      "| %zu | %.3f | %.3f | %.3f | %.2f |\n",
      accepted, in6 / n, in_rot / n, in_trans / n, nees_sum / n);
}

/** \brief The number in a scan's file name (full120.pcd: 120), or -1. */
int scanNumber(const std::string& name)
{
  const std::size_t slash = name.find_last_of('/');
  const std::string base = name.substr(slash == std::string::npos ? 0 : slash + 1);
  const std::size_t first = base.find_first_of("0123456789");
  return first == std::string::npos ? -1 : std::atoi(base.c_str() + first);
}

/** \brief Positions moved back by \a drift times each scan's number. */
void removeDrift(const Eigen::Vector3d& drift, const std::vector<std::string>& names,
                 std::vector<Eigen::Matrix4d>& poses)
{
  for (std::size_t k = 0; k < poses.size(); ++k)
    poses[k].topRightCorner<3, 1>() -= std::max(0, scanNumber(names[k])) * drift;
}

/** Every record judged against the reference poses; each row into \a csv_path too
 *  when given. */
std::vector<Row> judgeRecords(const std::vector<batch::Record>& records,
                              const std::vector<std::string>& names,
                              const std::vector<std::string>& paths,
                              const std::vector<Eigen::Matrix4d>& poses,
                              const std::string& csv_path)
{
  std::map<std::string, Cloud::Ptr> clouds;
  std::vector<Row> rows;
  FILE* csv = csv_path.empty() ? nullptr : std::fopen(csv_path.c_str(), "w");
  if (csv)
    std::fprintf(csv,
                 "pair,source,target,distance_m,overlap,converged,rre_deg,rte_m,nees,"
                 "nees_rot,nees_trans,sigma_rot_deg,sigma_trans_m\n");
  for (const batch::Record& r : records) {
    Row w;
    w.pair = r["pair"].get<std::size_t>();
    const int s = r["source_id"].get<int>(), t = r["target_id"].get<int>();
    w.source = names.at(s);
    w.target = names.at(t);
    const Eigen::Matrix4d truth = poses[t].inverse() * poses[s];
    w.distance = truth.topRightCorner<3, 1>().norm();
    w.overlap = overlap(*load(paths[s], clouds), load(paths[t], clouds), truth);
    w.ok = r.value("status", "") == "ok";
    w.converged = r.value("converged", false);
    if (w.ok)
      judge(r, truth, w);
    if (csv)
      std::fprintf(csv, "%zu,%s,%s,%.3f,%.3f,%d,%.4f,%.4f,%.3f,%.3f,%.3f,%.4f,%.4f\n",
                   w.pair, w.source.c_str(), w.target.c_str(), w.distance, w.overlap,
                   int(w.converged), w.rre, w.rte, w.nees, w.nees_rot, w.nees_trans,
                   w.sigma_rot_deg, w.sigma_trans_m);
    rows.push_back(w);
  }
  if (csv)
    std::fclose(csv);
  return rows;
}

/** Reads the records, scans and poses, judges every record and prints the summary. */
int runLoopClosure(pcl::phaser::bench::BenchArguments& args)
{
  const std::string records_path = args.text("--records"),
                    scans_path = args.text("--scans"),
                    poses_path = args.text("--poses");
  const double real_overlap = args.number("--real-overlap", 0.3);
  const std::vector<double> d = args.numbers("--reference-drift", {0, 0, 0});
  args.check(!records_path.empty() && !scans_path.empty() && !poses_path.empty(),
             "--records, --scans and --poses are required");
  args.check(d.size() == 3, "--reference-drift: three numbers DX,DY,DZ");
  if (!args.ok())
    return args.fail();
  std::vector<batch::Record> records;
  std::vector<std::string> names, paths;
  std::vector<Eigen::Matrix4d> poses;
  std::string error = batch::readRecords(records_path, records, false);
  if (error.empty())
    error = batch::readTrajectory(scans_path, poses_path, names, paths, poses);
  if (!error.empty())
    return std::fprintf(stderr, "%s\n", error.c_str()), 2;
  removeDrift(Eigen::Vector3d(d[0], d[1], d[2]), names, poses);
  const std::vector<Row> rows =
      judgeRecords(records, names, paths, poses, args.text("--csv"));
  summarize(rows, real_overlap);
  return 0;
}

} // namespace

const pcl::phaser::bench::Subcommand pcl::phaser::bench::kLoopClosure = {
    "loop-closure",
    "pcl_phaser_batch's records judged against the trajectory's reference poses: "
    "errors, wrong accepted edges, NEES",
    nullptr,
    {{"--records", "R.jsonl", "the records of pcl_phaser_batch --scans ..."},
     {"--scans", "LIST", "the scan list the batch read"},
     {"--poses", "POSES", "the reference poses, one line per scan"},
     {"--csv", "FILE", "every pair as CSV"},
     {"--real-overlap", "F",
      "a candidate with at least this overlap is a real revisit (default 0.3)"},
     sharedOption("--reference-drift")},
    false,
    0,
    runLoopClosure};
