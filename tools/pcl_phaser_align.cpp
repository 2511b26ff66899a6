// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
/** \file pcl_phaser_align.cpp
 * \brief pcl_phaser_align: global registration of two point clouds with
 * pcl::PhaserRegistration, optionally refined by ICP.
 *
 *   pcl_phaser_align SOURCE TARGET [options]   (.pcd, .ply or KITTI .bin)
 *   pcl_phaser_align [--demo] [options]        (simulated LiDAR pair, known truth)
 *
 * Prints T_target_source (p_target = T p_source), the scores, the stage timings and,
 * when the truth is known (--gt, the demo), the rotation and translation errors; can
 * write the aligned source (-o), a red/green overlay (-m) and a PNG of it
 * (--screenshot), or print one JSON object (--json). Options and exit codes:
 * printHelp(). Helpers: pcl_phaser_align_{options,steps,help}.h,
 * pcl_phaser_align_screenshot.{h,cpp} and result_json.h (shared with the batch).
 */
#include "cloud_reading.h"
#include "pcl_phaser_align_help.h"
#include "pcl_phaser_align_icp.h"
#include "pcl_phaser_align_options.h"
#include "pcl_phaser_align_screenshot.h"
#include "pcl_phaser_align_steps.h"
#include "process_memory.h"
#include "result_json.h"
#include "scan_simulator.h"
#include "transform_file.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/common/transforms.h>
#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <unistd.h>

using namespace pcl::console;
namespace align = pcl::phaser::align_tool;
using pcl::phaser::JsonFields;
using pcl::phaser::JsonObject;
using namespace pcl::phaser::align_tool;

namespace {

const double kPi = 3.14159265358979323846;

struct Result {
  std::string error; ///< the message of the failure, for --json
  Stage global, icp;
  pcl::phaser::PhaserResult estimate;
  pcl::phaser::PhaserParameters params; ///< the settings the registration ran with
  std::size_t source_points = 0, target_points = 0;
  pcl::PointCloud<pcl::PointXYZRGB>::Ptr overlay;
  /** \brief ICP's transform when it ran and converged, else PHASER's. */
  const Eigen::Matrix4d& final() const
  {
    return (icp.converged ? icp.transform : global.transform);
  }
};

// ---- load, register, refine -------------------------------------------------------

bool loadCloud(const std::string& path, pcl::PCLPointCloud2& cloud,
               std::string& message)
{
  TicToc tt;
  tt.tic();
  print_highlight("Loading ");
  print_value("%s ", path.c_str());
  std::string error;
  if (!pcl::phaser::loadCloud(path, cloud, &error)) {
    print_info("[failed]\n");
    return (fail(message, kInput, "Cannot load the cloud: %s", error.c_str()), false);
  }
  print_info("[done, ");
  print_value("%g", tt.toc());
  print_info(" ms : ");
  print_value("%u", cloud.width * cloud.height);
  print_info(" points]\nAvailable dimensions: ");
  std::string names;
  for (const pcl::PCLPointField& field : cloud.fields)
    names += field.name + " ";
  print_value("%s\n", names.c_str());
  for (const char* axis : {"x", "y", "z"})
    if (!align::isFloatField(cloud, pcl::getFieldIndex(cloud, axis)))
      return (fail(message, kInput, "'%s' has no float32/float64 %s field.",
                   path.c_str(), axis),
              false);
  if (cloud.width * cloud.height == 0)
    return (fail(message, kInput, "'%s' holds no points.", path.c_str()), false);
  return (true);
}

/** The global registration of \a source onto \a target into \a res.global and
 *  res.estimate. */
template <typename PointT>
void registerGlobally(pcl::PhaserRegistration<PointT, PointT>& phaser,
                      const typename pcl::PointCloud<PointT>::Ptr& source,
                      const typename pcl::PointCloud<PointT>::Ptr& target,
                      const Options& opt, Result& res)
{
  const pcl::phaser::PhaserParameters& params = opt.params;
  phaser.setParameters(params);
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  print_highlight("Registering ");
  print_info("%zu source to %zu target points as %s (bandwidth %d, grid %d, passes %d, "
             "threads %u, center %s) ",
             source->size(), target->size(),
             pcl::traits::has_intensity_v<PointT> ? "PointXYZI" : "PointXYZ",
             params.bandwidth, params.spatial_grid_size, params.passes,
             static_cast<unsigned>(
                 pcl::phaser::resolveThreadCount(int(phaser.getNumberOfThreads()))),
             pcl::phaser::centerName(params.projection_center));
  if (params.max_tilt_deg > 0.0)
    print_info("with a max tilt %g deg ", params.max_tilt_deg);
  TicToc tt;
  tt.tic();
  pcl::PointCloud<PointT> aligned;
  phaser.align(aligned);
  res.global.time_ms = tt.toc();
  res.global.ran = true;
  res.global.converged = phaser.hasConverged();
  res.global.transform = phaser.getFinalTransformation().template cast<double>();
  res.estimate = phaser.getResult();
  res.params = phaser.getParameters();
  print_info("[done, ");
  print_value("%g", res.global.time_ms);
  print_info(" ms : %s]\n", res.global.converged ? "converged" : "NOT converged");
}

/** The finite source points moved by the final transform in red, the target in green.
 */
template <typename PointT>
pcl::PointCloud<pcl::PointXYZRGB>::Ptr overlayOf(const pcl::PointCloud<PointT>& source,
                                                 const pcl::PointCloud<PointT>& target,
                                                 const Eigen::Matrix4d& T)
{
  pcl::PointCloud<PointT> moved;
  pcl::transformPointCloud(source, moved, T);
  auto overlay = pcl::make_shared<pcl::PointCloud<pcl::PointXYZRGB>>();
  overlay->reserve(moved.size() + target.size());
  for (const PointT& p : moved)
    overlay->push_back(pcl::PointXYZRGB(p.x, p.y, p.z, 255, 0, 0));
  for (const PointT& p : target)
    overlay->push_back(pcl::PointXYZRGB(p.x, p.y, p.z, 0, 160, 0));
  return overlay;
}

/** ICP from res.global's pose into \a res.icp with align::toolIcpSettings(): the
 *  clouds thinned, the correspondence distance from the global pose's covariance.
 *  \return kOk, or kUsage (after fail()) when the ICP module cannot be loaded */
template <typename PointT>
int refineWithIcp(const typename pcl::PointCloud<PointT>::Ptr& source,
                  const typename pcl::PointCloud<PointT>::Ptr& target,
                  const Options& opt, pcl::PhaserRegistration<PointT, PointT>& phaser,
                  Result& res)
{
  print_highlight("Refining with %s ICP ",
                  opt.icp_point ? "point-to-point" : "point-to-plane");
  align::IcpSettings icp = align::toolIcpSettings(opt.icp_distance, opt.icp_point,
                                                  phaser.getCovariance(), *source);
  icp.threads = phaser.getNumberOfThreads();
  align::IcpRun run;
  std::string why;
  if (!align::refineInModule<PointT>(source, target, res.global.transform, icp, res.icp,
                                     run, why))
    return (print_info("[failed]\n"),
            fail(res.error, kUsage, "Cannot refine with ICP: %s", why.c_str()));
  print_info("(%zu + %zu points, correspondences within %.3g m) [done, ",
             run.source_points, run.target_points, icp.max_distance);
  print_value("%g", res.icp.time_ms);
  print_info(" ms : %d iterations, %s]\n", run.iterations,
             res.icp.converged ? "converged" : "NOT converged");
  return (kOk);
}

template <typename PointT>
int compute(const pcl::PCLPointCloud2& source_blob,
            const pcl::PCLPointCloud2& target_blob, const Options& opt, Result& res)
{
  using Cloud = pcl::PointCloud<PointT>;
  const typename Cloud::Ptr source = align::toFiniteCloud<PointT>(source_blob);
  const typename Cloud::Ptr target = align::toFiniteCloud<PointT>(target_blob);
  if (source->empty() || target->empty())
    return (fail(res.error, kInput, "The %s cloud has no finite points.",
                 source->empty() ? "source" : "target"));
  res.source_points = source->size();
  res.target_points = target->size();
  pcl::PhaserRegistration<PointT, PointT> phaser;
  registerGlobally<PointT>(phaser, source, target, opt, res);
  if (opt.icp && res.global.converged)
    if (const int rc = refineWithIcp<PointT>(source, target, opt, phaser, res))
      return (rc);
  res.overlay = overlayOf(*source, *target, res.final());
  return (kOk);
}

// ---- report ---------------------------------------------------------------------

void printStage(const char* title, const Stage& s)
{
  print_highlight("%s", title);
  print_info(" T_target_source (%s):\n", s.converged ? "converged" : "NOT converged");
  for (int r = 0; r < 4; ++r)
    print_value("    %12.6f %12.6f %12.6f %12.6f\n", s.transform(r, 0),
                s.transform(r, 1), s.transform(r, 2), s.transform(r, 3));
  if (std::isfinite(s.rre_deg)) {
    print_info("    rotation error RRE: ");
    print_value("%.4f deg", s.rre_deg);
    print_info("   translation error RTE: ");
    print_value("%.4f m\n", s.rte_m);
  }
}

void printReport(const Result& res)
{
  const pcl::phaser::PhaserDiagnostics& diagnostics = res.estimate.diagnostics;
  const pcl::phaser::Verification& verification = diagnostics.verification;
  const pcl::phaser::StageTimes& times = diagnostics.times;
  printStage("PHASER", res.global);
  print_info(
      "    rotation score %.4f, translation score %.4f, passes %d\n"
      "    verification: inliers %.3f, free-space violations %.3f / %.3f, constraint "
      "%.3f (%d samples): %s\n"
      "    stages (ms): target %.1f, sampling %.1f, sht %.1f, so3 %.1f, "
      "refinement %.1f, translation %.1f, orientation %.1f, verification %.1f; "
      "total %.1f\n",
      diagnostics.rotation_score, diagnostics.translation_score, diagnostics.passes,
      verification.inlier_fraction, verification.free_space_violation,
      verification.reverse_free_space_violation, verification.constraint,
      diagnostics.verification_samples,
      diagnostics.verified ? "verified" : "NOT verified", times.target, times.sampling,
      times.sht, times.so3, times.refinement, times.translation, times.orientation,
      times.verification, res.global.time_ms);
  if (res.icp.ran)
    printStage("After ICP", res.icp);
}

/** \brief A stage as {"transformation", "converged", "time_ms"} plus "rre_deg" and
 * "rte_m" when its errors are known. */
JsonObject stageJson(const Stage& s)
{
  JsonObject o;
  JsonFields{o}("transformation", s.transform);
  o["converged"] = s.converged;
  o["time_ms"] = s.time_ms;
  if (std::isfinite(s.rre_deg)) {
    o["rre_deg"] = s.rre_deg;
    o["rte_m"] = s.rte_m;
  }
  return (o);
}

std::string toJson(const Result& res, const Options& opt, int code, double total_ms)
{
  JsonObject o;
  if (res.global.ran) {
    o = stageJson(res.global);
    pcl::phaser::visitResultFields(res.estimate, JsonFields{o});
    o["source_points"] = res.source_points;
    o["target_points"] = res.target_points;
    o["parameters"] = pcl::phaser::parametersJson(res.params);
    if (res.icp.ran) {
      o["icp"] = stageJson(res.icp);
      o["icp"]["method"] = opt.icp_point ? "point_to_point" : "point_to_plane";
    }
  }
  if (opt.demo)
    o["demo_seed"] = opt.seed;
  o["total_ms"] = total_ms;
  if (code != kOk)
    o["error"] = opt.error.empty() ? res.error : opt.error;
  o["exit_code"] = code;
  return (o.dump(-1, ' ', false, JsonObject::error_handler_t::replace));
}

// ---- output -----------------------------------------------------------------------

/** \brief Write -o, -m and --screenshot. */
int saveOutputs(const Options& opt, pcl::PCLPointCloud2& source_blob, Result& res)
{
  TicToc tt;
  std::string error;
  const auto done = [&](std::size_t points) {
    print_info("[done, ");
    print_value("%g", tt.toc());
    print_info(" ms : ");
    print_value("%zu", points);
    print_info(" points]\n");
  };
  if (!opt.output.empty()) {
    tt.tic();
    print_highlight("Saving aligned source, all fields, ");
    print_value("%s ", opt.output.c_str());
    align::transformBlob(source_blob, res.final());
    if (!pcl::phaser::saveCloud(opt.output, source_blob, &error))
      return (print_info("[failed]\n"),
              fail(res.error, kOutput, "Cannot write '%s': %s", opt.output.c_str(),
                   error.c_str()));
    done(static_cast<std::size_t>(source_blob.width) * source_blob.height);
  }
  if (!opt.overlay.empty()) {
    tt.tic();
    print_highlight("Saving overlay, source red and target green, ");
    print_value("%s ", opt.overlay.c_str());
    if (!pcl::phaser::saveCloud(opt.overlay, *res.overlay, &error))
      return (print_info("[failed]\n"),
              fail(res.error, kOutput, "Cannot write '%s': %s", opt.overlay.c_str(),
                   error.c_str()));
    done(res.overlay->size());
    print_info("View it with: ");
    print_value("pcl_viewer %s\n", opt.overlay.c_str());
  }
  if (!opt.screenshot.empty()) {
    tt.tic();
    print_highlight("Rendering the overlay ");
    print_value("%s ", opt.screenshot.c_str());
    if (!pcl::phaser::saveOverlayScreenshot(res.overlay, opt.screenshot, opt.width,
                                            opt.height, error))
      return (print_info("[failed]\n"), fail(res.error, kOutput, "Cannot save '%s': %s",
                                             opt.screenshot.c_str(), error.c_str()));
    done(res.overlay->size());
  }
  return (kOk);
}

/** The demo pair of \a opt.seed into \a source, \a target and \a truth. */
int simulateDemo(const Options& opt, pcl::PCLPointCloud2& source,
                 pcl::PCLPointCloud2& target, Eigen::Matrix4d& truth,
                 std::string& message)
{
  TicToc tt;
  tt.tic();
  print_highlight("Demo: ");
  print_info("simulating a LiDAR pair, seed %d ", opt.seed);
  try {
    const pcl::phaser::ScanPair pair =
        pcl::phaser::makeDemoPair(static_cast<unsigned>(opt.seed));
    pcl::toPCLPointCloud2(pair.source, source);
    pcl::toPCLPointCloud2(pair.target, target);
    truth = pair.T_target_source;
  } catch (const std::exception& e) {
    print_info("[failed]\n");
    return (fail(message, kInput, "The demo simulation failed: %s", e.what()));
  }
  print_info("[done, ");
  print_value("%g", tt.toc());
  print_info(" ms : %u + %u points; truth: %.1f deg, %.2f m]\n", source.width,
             target.width,
             Eigen::AngleAxisd(truth.topLeftCorner<3, 3>()).angle() * 180.0 / kPi,
             truth.topRightCorner<3, 1>().norm());
  return (kOk);
}

/** kOk when the demo's errors are within its bounds, else kDemoMissed (printed). */
int checkDemo(Result& res)
{
  const bool global_ok =
      res.global.rre_deg <= demo_rre_deg && res.global.rte_m <= demo_rte_m;
  const bool icp_ok =
      res.icp.rre_deg <= demo_icp_rre_deg && res.icp.rte_m <= demo_icp_rte_m;
  if (!global_ok || !icp_ok)
    return (fail(res.error, kDemoMissed,
                 "Demo FAILED: %s is %.3g deg / %.3g m from the truth; the bound is %g "
                 "deg / %g m.",
                 global_ok ? "ICP" : "PHASER",
                 global_ok ? res.icp.rre_deg : res.global.rre_deg,
                 global_ok ? res.icp.rte_m : res.global.rte_m,
                 global_ok ? demo_icp_rre_deg : demo_rre_deg,
                 global_ok ? demo_icp_rte_m : demo_rte_m));
  print_highlight("Demo passed: ");
  print_info("PHASER within %g deg / %g m and ICP within %g deg / %g m of the truth.\n",
             demo_rre_deg, demo_rte_m, demo_icp_rre_deg, demo_icp_rte_m);
  return (kOk);
}

int run(const Options& opt, Result& res)
{
  pcl::PCLPointCloud2 source, target;
  Eigen::Matrix4d truth = Eigen::Matrix4d::Identity();
  bool has_truth = opt.demo;
  std::string error;
  if (opt.demo) {
    if (const int rc = simulateDemo(opt, source, target, truth, res.error))
      return (rc);
  } else {
    if (!opt.gt.empty() && !pcl::phaser::loadTransform(opt.gt, truth, &error))
      return (fail(res.error, kInput, "Cannot use --gt: %s", error.c_str()));
    has_truth = !opt.gt.empty();
    if (!loadCloud(opt.source, source, res.error) ||
        !loadCloud(opt.target, target, res.error))
      return (kInput);
  }
  const bool intensity = pcl::getFieldIndex(source, "intensity") >= 0 &&
                         pcl::getFieldIndex(target, "intensity") >= 0;
  if (const int rc = intensity ? compute<pcl::PointXYZI>(source, target, opt, res)
                               : compute<pcl::PointXYZ>(source, target, opt, res))
    return (rc);
  if (has_truth) {
    align::computeErrors(res.global, truth);
    if (res.icp.ran)
      align::computeErrors(res.icp, truth);
  }
  printReport(res);
  if (!res.global.converged || (res.icp.ran && !res.icp.converged))
    return (fail(res.error, kNotConverged, "%s did not converge; nothing was written.",
                 res.global.converged ? "ICP" : "PHASER"));
  if (const int rc = saveOutputs(opt, source, res))
    return (rc);
  if (opt.demo)
    return (checkDemo(res));
  return (kOk);
}

} // namespace

int main(int argc, char** argv)
{
  pcl::phaser::preferHugePages();
  if (find_switch(argc, argv, "-h") || find_switch(argc, argv, "--help")) {
    printHelp(argv[0]);
    return (kOk);
  }
  if (find_switch(argc, argv, "--print-parameters")) {
    std::printf("%s", parameterTable().c_str());
    return (kOk);
  }
  // --json: stdout carries the JSON object only. Everything else, ours, PCL's and
  // VTK's, goes to stderr: file descriptor 1 points there until the end.
  const bool json_mode = find_switch(argc, argv, "--json");
  const int json_fd = json_mode ? dup(STDOUT_FILENO) : -1;
  if (json_fd >= 0) {
    dup2(STDERR_FILENO, STDOUT_FILENO);
    std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ); // keep the order of the messages
  }
  print_info("PHASER global registration of two point clouds. For more information, "
             "use: %s -h\n",
             argv[0]);
  TicToc tt;
  tt.tic();
  Options opt;
  Result res;
  int code = parseOptions(argc, argv, opt);
  if (code == kOk)
    code = run(opt, res);
  const double total_ms = tt.toc();
  if (code == kOk || res.global.ran) {
    print_info("Total time: ");
    print_value("%g", total_ms);
    print_info(" ms\n");
  }
  if (json_fd >= 0) {
    std::fflush(stdout);
    dup2(json_fd, STDOUT_FILENO);
    close(json_fd);
    std::printf("%s\n", toJson(res, opt, code, total_ms).c_str());
  }
  return (code);
}
