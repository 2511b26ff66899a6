/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_align and the parameter table: its option limits are the library's,
 * --threads 0 means automatic as in the library, and doc/parameters.md holds the table
 * the code prints (--print-parameters).
 */
#include <pcl_phaser/core/parameters.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

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

Output run(const std::string& args, bool merge)
{
  const std::string command = std::string(PCL_PHASER_ALIGN_BIN) + " " + args +
                              (merge ? " 2>&1" : " 2>/dev/null");
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
  EXPECT_TRUE(has(help.text, "spherical bandwidth, 2..256")) << help.text;
  EXPECT_TRUE(has(help.text, "worker threads, 0..64, 0: one per hardware thread"))
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
  EXPECT_TRUE(has(help.text, "0..180, 0: off")) << help.text;
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
