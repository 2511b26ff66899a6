/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_align and the parameter table: its option limits are the library's,
 * --threads 0 means automatic as in the library, and doc/parameters.md holds the table
 * the code prints (--print-parameters); pcl_phaser_batch takes the same engine options
 * (engine_options.h) with the same messages.
 */
#include "engine_options.h"

#include <pcl_phaser/core/parameters.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

#ifndef PCL_PHASER_ALIGN_BIN
#error "PCL_PHASER_ALIGN_BIN must name the pcl_phaser_align binary"
#endif
#ifndef PCL_PHASER_DOC_DIR
#error "PCL_PHASER_DOC_DIR must name the doc directory"
#endif

namespace {

struct Output {
  int code = -1;
  std::string text; ///< stdout, and stderr when \a merge
};

Output runTool(const std::string& tool, const std::string& args, bool merge)
{
  const std::string command = tool + " " + args + (merge ? " 2>&1" : " 2>/dev/null");
  Output out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe)
    return out;
  char buffer[4096];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0)
    out.text.append(buffer, n);
  const int status = pclose(pipe);
  out.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

Output run(const std::string& args, bool merge)
{
  return runTool(PCL_PHASER_ALIGN_BIN, args, merge);
}

bool has(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

} // namespace

TEST(ParameterOptions, DocumentedTableIsTheCodesTable)
{
  const Output table = run("--print-parameters", false);
  ASSERT_EQ(table.code, 0);
  for (const pcl::phaser::ParameterRange& r : pcl::phaser::kParameterRanges)
    EXPECT_TRUE(has(table.text, std::string("| `") + r.name + "` |")) << r.name;
  std::ifstream file(std::string(PCL_PHASER_DOC_DIR) + "/parameters.md");
  ASSERT_TRUE(file.good()) << "doc/parameters.md is missing";
  std::stringstream doc;
  doc << file.rdbuf();
  EXPECT_TRUE(has(doc.str(), table.text))
      << "doc/parameters.md differs from the code; regenerate its table with "
         "pcl_phaser_align --print-parameters:\n"
      << table.text;
}

TEST(ParameterOptions, LimitsAreTheLibrarys)
{
  const Output help = run("-h", true);
  EXPECT_TRUE(has(help.text, "-b B, --bandwidth")) << help.text;
  EXPECT_TRUE(has(help.text, "spherical bandwidth B: a 2B x 2B grid on the sphere; "
                             "2..256 (default: 64)"))
      << help.text;
  EXPECT_TRUE(has(help.text, "worker threads (0: one per hardware thread); 0..64"))
      << help.text;
  for (const char* args : {"--demo -b 1", "--demo -b 257"}) {
    const Output bad = run(args, true);
    EXPECT_EQ(bad.code, 1) << args;
    EXPECT_TRUE(has(bad.text, "expected an integer in 2..256 (spherical bandwidth"))
        << bad.text;
  }
  const Output threads = run("--demo --threads 65", true);
  EXPECT_EQ(threads.code, 1);
  EXPECT_TRUE(has(threads.text, "expected an integer in 0..64 (worker threads (0: one "
                                "per hardware thread))"))
      << threads.text;
}

TEST(ParameterOptions, ThreadsZeroIsAutomatic)
{
  const Output out = run("--demo --threads 0 -m /dev/null.pcd", true);
  EXPECT_FALSE(has(out.text, "Invalid value")) << out.text;
  const std::string automatic =
      "threads " + std::to_string(pcl::phaser::resolveThreadCount(0)) + ", center";
  EXPECT_TRUE(has(out.text, automatic)) << out.text;
}

TEST(ParameterOptions, RegionIsFourNumbersWithAPositiveRadius)
{
  for (const char* value : {"1,2,3", "1,2,3,0", "1,2,3,-5", "a,b,c,d", "1,2,3,4,5",
                            "2e6,0,0,5", "1,2,3,nan", "1;2;3;4"}) {
    const Output bad = run(std::string("--demo --region '") + value + "'", true);
    EXPECT_EQ(bad.code, 1) << value;
    EXPECT_TRUE(has(bad.text, "Invalid --region")) << bad.text;
  }
  EXPECT_TRUE(has(run("-h", true).text, "--region X,Y,Z,R"));
  // The demo's source sensor is 2.8 m from the target's: inside a 10 m region about it.
  const Output good = run("--demo --region 0,0,0,10 -m /dev/null.pcd", true);
  EXPECT_EQ(good.code, 0) << good.text;
}

TEST(ParameterOptions, MaxTiltIsParsedAndRefusedOutsideItsRange)
{
  const Output help = run("-h", true);
  EXPECT_TRUE(has(help.text, "--max-tilt DEG")) << help.text;
  EXPECT_TRUE(has(help.text, "(0: off); 0..180 deg")) << help.text;
  for (const char* args :
       {"--demo --max-tilt 181", "--demo --max-tilt -1", "--demo --max-tilt ten",
        "--demo --max-tilt nan", "--demo --max-tilt 10x"}) {
    const Output bad = run(args, true);
    EXPECT_EQ(bad.code, 1) << args;
    EXPECT_TRUE(has(bad.text, "Invalid --max-tilt")) << bad.text;
    EXPECT_TRUE(has(bad.text, "expected degrees in 0..180 (gravity prior")) << bad.text;
  }
  const Output missing = run("--demo --max-tilt", true);
  EXPECT_EQ(missing.code, 1);
  EXPECT_TRUE(has(missing.text, "needs a value")) << missing.text;
  // Within the range the demo runs (its pair is tilted under 3 deg: found).
  const Output good = run("--demo --max-tilt 10 -m /dev/null.pcd", true);
  EXPECT_FALSE(has(good.text, "Invalid")) << good.text;
  EXPECT_TRUE(has(good.text, "max tilt 10 deg")) << good.text;
}

TEST(EngineOptions, EveryRowHasItsOptionAndTheAliasesStay)
{
  using pcl::phaser::findEngineOption;
  for (const pcl::phaser::ParameterRange& r : pcl::phaser::kParameterRanges) {
    std::string flag = std::string("--") + r.name;
    std::replace(flag.begin(), flag.end(), '_', '-');
    const int k = findEngineOption(flag);
    ASSERT_GE(k, 0) << flag;
    EXPECT_EQ(pcl::phaser::engineOptions()[k].range, &r) << flag;
  }
  for (const char* alias :
       {"-b", "--grid", "--passes", "--threads", "--max-tilt", "--center", "--region",
        "--normalized-refinement", "--projection-center", "--channels"})
    EXPECT_GE(findEngineOption(alias), 0) << alias;
  EXPECT_EQ(findEngineOption("--icp-dist"), -1);
}

TEST(EngineOptions, RegionFieldsRefineTheRegionAndAreValidated)
{
  pcl::phaser::CommandLine line;
  const char* argv[] = {"tool",    "--region-x",     "5", "--region",
                        "1,2,3,4", "--sensor-range", "30"};
  ASSERT_EQ(pcl::phaser::collectArguments(7, const_cast<char**>(argv), {}, {}, line),
            "");
  pcl::phaser::EngineArguments& args = line.engine;
  pcl::phaser::PhaserParameters p;
  ASSERT_EQ(pcl::phaser::setEngineOptions(args, p), "");
  ASSERT_TRUE(p.region.has_value());
  EXPECT_EQ(p.region->x, 5.0); // the field after --region, whatever the order given
  EXPECT_EQ(p.region->y, 2.0);
  EXPECT_EQ(p.region->radius, 4.0);
  EXPECT_EQ(p.region->sensor_range, 30.0);
  pcl::phaser::PhaserParameters q;
  args.erase(pcl::phaser::findEngineOption("--region"));
  EXPECT_TRUE(has(pcl::phaser::setEngineOptions(args, q), "region_radius = 0"));
}

TEST(ParameterOptions, TypedOptionsRefuseBadNamesWithTheAllowedOnes)
{
  const struct {
    const char* args;
    const char* message;
  } cases[] = {
      {"--projection-center bogus",
       "Invalid --projection-center 'bogus': expected one of sensor, centroid, auto"},
      {"--center middle",
       "Invalid --center 'middle': expected one of sensor, centroid"},
      {"--normalized-refinement maybe",
       "Invalid --normalized-refinement 'maybe': expected true or false"},
      {"--channels range,bogus",
       "Invalid --channels 'range,bogus': expected all, or "
       "any of range, intensity, reflectivity, ambient, color"},
      {"--channels -1", "Invalid --channels '-1'"}};
  for (const auto& c : cases) {
    const Output bad = run(std::string("--demo ") + c.args, true);
    EXPECT_EQ(bad.code, 1) << c.args;
    EXPECT_TRUE(has(bad.text, c.message)) << bad.text;
  }
  const Output help = run("-h", true);
  EXPECT_TRUE(has(help.text, "--normalized-refinement BOOL")) << help.text;
  EXPECT_TRUE(has(help.text, "--center MODE, --projection-center")) << help.text;
  EXPECT_TRUE(has(help.text, "sensor, centroid, auto (default: auto)")) << help.text;
  EXPECT_TRUE(has(help.text, "--channels LIST")) << help.text;
}

TEST(ParameterOptions, TypedOptionsReachTheEngine)
{
  // The settings the registration ran with, in --json: every row of the table.
  const Output plain = run("--demo --json -m /dev/null.pcd", false);
  const Output off = run("--demo --json -m /dev/null.pcd --normalized-refinement off "
                         "--projection-center sensor --channels range",
                         false);
  ASSERT_EQ(plain.code, 0) << plain.text;
  ASSERT_EQ(off.code, 0) << off.text;
  for (const pcl::phaser::ParameterRange& r : pcl::phaser::kParameterRanges)
    EXPECT_TRUE(has(plain.text, std::string("\"") + r.name + "\":")) << r.name;
  EXPECT_TRUE(has(plain.text, "\"normalized_refinement\":true")) << plain.text;
  EXPECT_TRUE(has(plain.text, "\"projection_center\":\"auto\"")) << plain.text;
  EXPECT_TRUE(has(plain.text, "\"channels\":\"all\"")) << plain.text;
  EXPECT_TRUE(has(off.text, "\"normalized_refinement\":false")) << off.text;
  EXPECT_TRUE(has(off.text, "\"projection_center\":\"sensor\"")) << off.text;
  EXPECT_TRUE(has(off.text, "\"channels\":\"range\"")) << off.text;
}

#ifdef PCL_PHASER_BATCH_BIN
namespace {
/** \brief \a v as an option's value: "3", "0.5", "-1e+06". */
std::string number(double v)
{
  std::ostringstream out;
  out << std::setprecision(10) << v;
  return out.str();
}

/** \brief What pcl_phaser_align says of \a args: its last line from the first
 *  letter, without the final period. */
std::string alignMessage(const std::string& args)
{
  std::string text = run("missing_s.pcd missing_t.pcd " + args, true).text;
  text = text.substr(text.find_first_of("IO")); // Invalid ..., Option ...
  return text.substr(0, text.find_last_of('.'));
}

Output batch(const std::string& args)
{
  return runTool(PCL_PHASER_BATCH_BIN, "--pairs /dev/null --print-pairs " + args, true);
}
} // namespace

TEST(EngineOptions, BothToolsRefuseABadValueWithTheSameMessage)
{
  std::vector<std::string> cases = {"-b 1",         "--grid x",     "--center middle",
                                    "--region 1,2", "--threads 65", "--max-tilt -1",
                                    "--region-x 5", "-b 32 -b 16",  "--passes"};
  for (const pcl::phaser::EngineOption& o : pcl::phaser::engineOptions())
    if (o.range) // above the range, or below it when it is unbounded
      cases.push_back(
          o.flag + " " +
          number(std::isinf(o.range->max) ? o.range->min - 1 : o.range->max + 1));
  for (const std::string& args : cases) {
    const Output other = batch(args);
    EXPECT_EQ(run("missing_s.pcd missing_t.pcd " + args, false).code, 1) << args;
    EXPECT_EQ(other.code, 1) << args << ": " << other.text;
    const std::string message = alignMessage(args);
    if (args != "--region-x 5") { // else the engine's reason: region_radius = 0
      EXPECT_TRUE(has(message, args.substr(0, args.find(' ')))) << message;
    }
    EXPECT_TRUE(has(other.text, message)) << args << ": " << other.text;
  }
}

TEST(EngineOptions, EveryOptionWorksInBothTools)
{
  const std::string batch_help = runTool(PCL_PHASER_BATCH_BIN, "-h", true).text;
  const std::string align_help = run("-h", true).text;
  for (const pcl::phaser::EngineOption& o : pcl::phaser::engineOptions()) {
    std::vector<std::string> values = {"1,2,3,4"}; // --region
    if (o.range) {
      values = {pcl::phaser::parameterText(*o.range, o.range->min, 10)};
      if (!std::isinf(o.range->max))
        values.push_back(pcl::phaser::parameterText(*o.range, o.range->max, 10));
    }
    for (const std::string& value : values) {
      const std::string args =
          o.flag + " " + value +
          (o.range && o.range->in_region ? " --region 0,0,0,9" : "");
      // Past the options: the missing clouds (2); the batch prints its empty list (0).
      EXPECT_EQ(run("missing_s.pcd missing_t.pcd " + args, false).code, 2) << args;
      EXPECT_EQ(batch(args).code, 0) << args << ": " << batch(args).text;
    }
    for (const std::string* help : {&align_help, &batch_help})
      EXPECT_TRUE(
          has(*help, (o.alias ? o.alias : o.flag) + std::string(" ") + o.value_name))
          << o.flag;
  }
}
#endif
