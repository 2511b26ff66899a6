// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
// pcl_phaser_align's help text, its defaults and ranges read from the code.
#include "pcl_phaser_align_help.h"
#include "pcl_phaser_align_icp.h"
#include "pcl_phaser_align_options.h"

#include <pcl_phaser/phaser_registration.h>

#include <pcl/console/print.h>

#include <climits>

using namespace pcl::console;
using namespace pcl::phaser::align_tool;

namespace {

/** The ICP and output options of the help. */
void printOutputHelp()
{
  print_info(
      "    -icp                = refine with point-to-plane ICP "
      "(pcl::IterativeClosestPointWithNormals, target normals\n"
      "                          from %d neighbors) from the PHASER estimate: at most "
      "%d iterations, transformation epsilon %g,\n"
      "                          the target reduced to one point per voxel of a "
      "quarter of --icp-dist, the source to half;\n"
      "                          correspondences within %g sigma of the PHASER "
      "covariance, at least one target voxel\n"
      "    --icp-point         = with -icp: plain point-to-point "
      "pcl::IterativeClosestPoint instead\n"
      "    --icp-dist D        = ICP's largest correspondence distance in m, and the "
      "scale of its voxels (default: %g)\n"
      "    -o FILE             = save SOURCE moved by the final transform, all fields "
      "kept (.pcd/.ply/.bin)\n"
      "    -m FILE             = save the overlay, aligned source red + target green "
      "(PointXYZRGB, .pcd/.ply); view: pcl_viewer FILE\n"
      "    --screenshot F.png  = render the overlay top-down to a PNG; needs X, e.g. "
      "xvfb-run -a -s \"-screen 0 1280x1024x24\" ...\n"
      "    --size WxH          = screenshot size in pixels, 16..8192 (default: %dx%d)\n"
      "    --gt FILE           = the true T_target_source (4x4 or 3x4 text): report "
      "RRE (deg) and RTE (m)\n"
      "    --json              = print one JSON object on stdout, everything else on "
      "stderr\n",
      icp_normal_neighbors, icp_iterations, icp_transformation_epsilon,
      icp_distance_sigmas, default_icp_distance, default_width, default_height);
}

} // namespace

namespace pcl::phaser::align_tool {

void printHelp(const char* program)
{
  print_error("Syntax is: %s SOURCE TARGET <options>\n"
              "       or: %s [--demo] <options>\n",
              program, program);
  const pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ> d; // the class defaults
  print_info(
      "  Registers SOURCE onto TARGET (.pcd, .ply or KITTI .bin) with PHASER and "
      "prints\n  T_target_source (p_target = T * p_source). Engine settings "
      "(doc/parameters.md; --threads 0: here %u, the demo's default: %d):\n%s"
      "    --print-parameters  = print the range of every setting as a Markdown "
      "table\n",
      static_cast<unsigned>(pcl::phaser::resolveThreadCount(0)), default_demo_threads,
      pcl::phaser::engineOptionsHelp(d.getParameters()).c_str());
  printOutputHelp();
  print_info(
      "    --demo              = the embedded demo, also run with no arguments: a "
      "simulated LiDAR pair, -icp,\n"
      "                          errors against the truth, overlay in ./%s (or -m). "
      "It fails (exit 4)\n"
      "                          unless PHASER is within %g deg / %g m and ICP within "
      "%g deg / %g m of the truth\n"
      "    --seed S            = demo seed, 0..%d (default: %d)\n"
      "    -h, --help          = this help\n"
      "  Exit codes: 0 success, 1 usage or bad option, 2 bad input file (cloud or "
      "--gt), 3 not converged (nothing is\n"
      "  written), 4 demo outside its bounds, 5 output not written (also: no X "
      "display for --screenshot).\n",
      default_demo_overlay, demo_rre_deg, demo_rte_m, demo_icp_rre_deg, demo_icp_rte_m,
      INT_MAX, default_seed);
}

} // namespace pcl::phaser::align_tool
