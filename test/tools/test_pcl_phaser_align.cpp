/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * End-to-end tests of the pcl_phaser_align tool: the built binary (compile definition
 * PCL_PHASER_ALIGN_BIN) is run through std::system, and its exit code, its output and
 * the files it writes are checked. Inputs are simulated scans written to a temporary
 * directory (simulator/scan_simulator.h), plus the shared real scans when present.
 */
#include "../registration/test_data.h"
#include "cloud_reading.h"
#include "json_test_reader.h"
#include "result_field_keys.h"
#include "scan_simulator.h"
#include "transform_file.h"

#include <pcl/common/io.h>
#include <pcl/point_types.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <utility>
#include <vector>

#ifndef PCL_PHASER_ALIGN_BIN
#error "PCL_PHASER_ALIGN_BIN must name the pcl_phaser_align binary"
#endif

namespace {

namespace fs = std::filesystem;
using json_test::Json;
using json_test::JsonReader;
using json_test::toMatrix;
using pcl::phaser::test::kResultFieldKeys;
using pcl::phaser::test::kStageKeys;

double rotationErrorDeg(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b)
{
  const Eigen::Matrix3d d =
      b.topLeftCorner<3, 3>().transpose() * a.topLeftCorner<3, 3>();
  return (Eigen::AngleAxisd(d).angle() * 180.0 / 3.14159265358979323846);
}

/** \brief Checks a stage object: a rigid 4x4 "transformation", "converged" and
 * "time_ms", and with \a truth, "rre_deg"/"rte_m" consistent with the matrix. */
void checkStage(const Json& stage, const Eigen::Matrix4d* truth, Eigen::Matrix4d& T)
{
  ASSERT_EQ(stage.type, Json::Type::Object);
  ASSERT_TRUE(toMatrix(stage.get("transformation"), T)) << "not a 4x4 matrix";
  EXPECT_TRUE((T.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).isZero(1e-12));
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  EXPECT_TRUE((R.transpose() * R).isIdentity(1e-5)) << R;
  ASSERT_TRUE(stage.get("converged"));
  EXPECT_EQ(stage.get("converged")->type, Json::Type::Bool);
  ASSERT_TRUE(stage.get("time_ms") && stage.get("time_ms")->isNumber());
  EXPECT_GT(stage.get("time_ms")->number, 0.0);
  if (!truth)
    return;
  const Json *rre = stage.get("rre_deg"), *rte = stage.get("rte_m");
  ASSERT_TRUE(rre && rre->isNumber() && rte && rte->isNumber());
  EXPECT_NEAR(rre->number, rotationErrorDeg(T, *truth), 1e-4);
  EXPECT_NEAR(rte->number,
              (T.topRightCorner<3, 1>() - truth->topRightCorner<3, 1>()).norm(), 1e-6);
}

// ---- running the tool -----------------------------------------------------------

struct ToolRun {
  int code = -1; ///< exit code; 128 + signal number when the process was killed
  std::string out, err;
};

/** \brief Parses what a run printed as one JSON object, into \a j, and checks it as a
 * stage (checkStage()), with \a T its transformation. */
void checkJsonRun(const ToolRun& r, const Eigen::Matrix4d* truth, Json& j,
                  Eigen::Matrix4d& T)
{
  ASSERT_TRUE(JsonReader(r.out).document(j)) << "stdout is not one JSON value:\n"
                                             << r.out;
  ASSERT_NO_FATAL_FAILURE(checkStage(j, truth, T));
}

std::string quote(const std::string& s)
{
  std::string q = "'";
  for (const char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return (q + "'");
}

std::string readFile(const fs::path& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return (s.str());
}

class PclPhaserAlign : public ::testing::Test {
protected:
  static fs::path dir_;
  static pcl::PointCloud<pcl::PointXYZINormal> source_;
  static pcl::PointCloud<pcl::PointXYZI> target_;
  static Eigen::Matrix4d truth_;

  /** \brief A smaller simulated pair (32 beams, 0.4 deg), written as src.pcd (with
   * normals, and one NaN point) and tgt.pcd, with its truth in truth.txt. */
  static void SetUpTestSuite()
  {
    dir_ = fs::temp_directory_path() /
           ("pcl_phaser_align_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    pcl::phaser::LidarParameters lidar;
    lidar.beams = 32;
    lidar.azimuth_step_deg = 0.4;
    const pcl::phaser::ScanPair pair = pcl::phaser::makeDemoPair(3, lidar);
    pcl::copyPointCloud(pair.source, source_);
    for (auto& p : source_)
      p.getNormalVector3fMap() = p.getVector3fMap().normalized();
    source_[0].x = source_[0].y = source_[0].z =
        std::numeric_limits<float>::quiet_NaN();
    source_.is_dense = false;
    target_ = pair.target;
    truth_ = pair.T_target_source;
    // Fields sorted by offset: PCL 1.13's PCD writer mis-pads a PointXYZINormal blob
    // (intensity is registered before normal_x but stored after it).
    pcl::PCLPointCloud2 blob;
    pcl::toPCLPointCloud2(source_, blob);
    std::sort(blob.fields.begin(), blob.fields.end(),
              [](const auto& a, const auto& b) { return (a.offset < b.offset); });
    ASSERT_TRUE(pcl::phaser::saveCloud((dir_ / "src.pcd").string(), blob));
    ASSERT_TRUE(pcl::phaser::saveCloud((dir_ / "tgt.pcd").string(), target_));
    std::ofstream truth(dir_ / "truth.txt");
    truth.precision(17);
    truth << truth_ << "\n";
    ASSERT_TRUE(truth.good());
  }
  static void TearDownTestSuite()
  {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  /** \brief Run `[prefix] pcl_phaser_align args` in the temporary directory. */
  static ToolRun run(const std::string& args, const std::string& prefix = "")
  {
    static int counter = 0;
    const fs::path out = dir_ / ("out" + std::to_string(counter) + ".txt");
    const fs::path err = dir_ / ("err" + std::to_string(counter++) + ".txt");
    const std::string command = "cd " + quote(dir_.string()) + " && " + prefix +
                                quote(PCL_PHASER_ALIGN_BIN) + " " + args + " >" +
                                quote(out.string()) + " 2>" + quote(err.string());
    const int status = std::system(command.c_str());
    ToolRun r;
    if (status != -1 && WIFEXITED(status))
      r.code = WEXITSTATUS(status);
    else if (status != -1 && WIFSIGNALED(status))
      r.code = 128 + WTERMSIG(status);
    r.out = readFile(out);
    r.err = readFile(err);
    return (r);
  }

  static std::string path(const std::string& name) { return ((dir_ / name).string()); }

  /** \brief Write the unfit inputs of BadInputsFailWithAMessage to the temporary
   * directory: garbage, empty, headerless or lying PCD and PLY files, and a non-rigid
   * transform. */
  static void writeBadInputFiles()
  {
    std::ofstream(path("garbage.pcd")) << "\x01\x02 this is not a point cloud \xff";
    std::ofstream(path("empty.pcd"));
    std::ofstream(path("x.xyz")) << "1 2 3\n";
    std::ofstream(path("notrigid.txt")) << "1 2 3 4\n5 6 7 8\n9 10 11 12\n0 0 0 1\n";
    const std::string header =
        "VERSION .7\nFIELDS %s\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 "
        "1\nWIDTH %d\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS "
        "%d\nDATA ascii\n";
    char buffer[512];
    std::snprintf(buffer, sizeof(buffer), header.c_str(), "x y z", 0, 0);
    std::ofstream(path("zero.pcd")) << buffer;
    std::snprintf(buffer, sizeof(buffer), header.c_str(), "a b c", 2, 2);
    std::ofstream(path("noxyz.pcd")) << buffer << "1 2 3\n4 5 6\n";
    std::snprintf(buffer, sizeof(buffer), header.c_str(), "x y z", 2, 2);
    std::ofstream(path("nan.pcd")) << buffer << "nan nan nan\nnan nan nan\n";
    // Files that crash, abort or exhaust PCL 1.13.0's readers in-process.
    std::ofstream(path("no_fields.pcd"))
        << "VERSION .7\nWIDTH 1\nPOINTS 1\nDATA ascii\n1 2 3\n";
    std::snprintf(buffer, sizeof(buffer), header.c_str(), "x y z", 1000000000,
                  1000000000);
    std::ofstream(path("lying_points.pcd"))
        << std::string(buffer).replace(std::string(buffer).find("ascii"), 5, "binary")
        << "123456789012";
    const std::string ply = "ply\nformat ascii 1.0\n";
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    const std::string grid = "obj_info num_cols 2\nobj_info num_rows 2\n";
    const std::string range_grid =
        "element range_grid 4\nproperty list uchar int vertex_indices\nend_header\n";
    std::ofstream(path("grid_too_small.ply"))
        << ply << "obj_info num_cols 1\nobj_info num_rows 1\nelement vertex 2\n"
        << xyz << "end_header\n1 2 3\n4 5 6\n";
    std::ofstream(path("indented_obj_info.ply"))
        << ply << " obj_info num_cols 2\nelement vertex 1\n"
        << xyz << "end_header\n1 2 3\n";
    std::ofstream(path("blue_before_red.ply"))
        << ply << "element vertex 2\n"
        << xyz
        << "property uchar blue\nproperty uchar green\nproperty uchar red\nend_header\n"
        << "1 2 3 4 5 6\n6 7 8 9 10 11\n";
    for (const char* index : {"357913941", "357913942"}) // a crash, a silent wrong read
      std::ofstream(path(std::string("range_grid_") + index + ".ply"))
          << ply << grid << "element vertex 2\n"
          << xyz << range_grid << "1 2 3\n4 5 6\n1 " << index << "\n0\n0\n1 0\n";
  }
};

fs::path PclPhaserAlign::dir_;
pcl::PointCloud<pcl::PointXYZINormal> PclPhaserAlign::source_;
pcl::PointCloud<pcl::PointXYZI> PclPhaserAlign::target_;
Eigen::Matrix4d PclPhaserAlign::truth_ = Eigen::Matrix4d::Identity();

// ---- tests ------------------------------------------------------------------------

TEST_F(PclPhaserAlign, HelpExitsZero)
{
  for (const char* flag : {"-h", "--help"}) {
    const ToolRun r = run(flag);
    EXPECT_EQ(r.code, 0) << flag;
    const std::string all = r.out + r.err;
    for (const char* word : {"--bandwidth", "--center", "-icp", "--json", "--demo",
                             "--screenshot", "Exit codes"})
      EXPECT_NE(all.find(word), std::string::npos) << word << " missing from " << flag;
  }
}

TEST_F(PclPhaserAlign, DemoWithoutArgumentsMeetsItsBoundsAndWritesTheOverlay)
{
  const ToolRun r = run("");
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("Demo passed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("pcl_viewer phaser_demo_overlay.pcd"), std::string::npos);
  // The errors of both stages are printed.
  std::size_t rre = 0, at = 0;
  while ((at = r.out.find("RRE", at)) != std::string::npos)
    ++rre, ++at;
  EXPECT_EQ(rre, 2u) << r.out;
  // The overlay: every demo point, source red then target green.
  pcl::PointCloud<pcl::PointXYZRGB> overlay;
  std::string error;
  ASSERT_TRUE(pcl::phaser::loadCloud(path("phaser_demo_overlay.pcd"), overlay, &error))
      << error;
  const pcl::phaser::ScanPair pair = pcl::phaser::makeDemoPair(1);
  ASSERT_EQ(overlay.size(), pair.source.size() + pair.target.size());
  std::size_t red = 0, green = 0;
  for (const auto& p : overlay) {
    red += p.r == 255 && p.g == 0 && p.b == 0;
    green += p.r == 0 && p.g == 160 && p.b == 0;
  }
  EXPECT_EQ(red, pair.source.size());
  EXPECT_EQ(green, pair.target.size());
}

TEST_F(PclPhaserAlign, DemoJsonHasTheErrorsOfBothStages)
{
  const ToolRun r = run("--demo --json -m demo_overlay.ply");
  const pcl::phaser::ScanPair pair = pcl::phaser::makeDemoPair(1);
  Json j;
  Eigen::Matrix4d T, T_icp;
  ASSERT_NO_FATAL_FAILURE(checkJsonRun(r, &pair.T_target_source, j, T));
  ASSERT_TRUE(j.get("icp"));
  ASSERT_NO_FATAL_FAILURE(checkStage(*j.get("icp"), &pair.T_target_source, T_icp));
  EXPECT_LT(j.get("rre_deg")->number, 2.0); // the demo's global bound (see the tool)
  EXPECT_LT(j.get("rte_m")->number, 0.2);
  EXPECT_LT(j.get("icp")->get("rre_deg")->number, 0.1);
  EXPECT_LT(j.get("icp")->get("rte_m")->number, 0.02);
  ASSERT_TRUE(j.get("exit_code") && j.get("exit_code")->isNumber());
  EXPECT_EQ(static_cast<int>(j.get("exit_code")->number), r.code);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("demo_overlay.ply")));
}

TEST_F(PclPhaserAlign, JsonIsOneObjectWithTheKeys)
{
  const ToolRun r = run("src.pcd tgt.pcd --gt truth.txt -icp --json");
  EXPECT_EQ(r.code, 0) << r.err;
  Json j;
  Eigen::Matrix4d T, T_icp;
  ASSERT_NO_FATAL_FAILURE(checkJsonRun(r, &truth_, j, T));
  EXPECT_TRUE(j.get("converged")->boolean);
  // The result's fields, the keys and order of the batch's records (visitResultFields).
  const auto first = std::find_if(j.object.begin(), j.object.end(), [](const auto& m) {
    return m.first == "covariance";
  });
  ASSERT_GE(j.object.end() - first, static_cast<long>(kResultFieldKeys.size()));
  for (std::size_t i = 0; i < kResultFieldKeys.size(); ++i)
    EXPECT_EQ(first[i].first, kResultFieldKeys[i]);
  ASSERT_EQ(j.get("covariance")->array.size(), 6u); // 6 x 6, row-major
  EXPECT_EQ(j.get("covariance")->array[5].array.size(), 6u);
  EXPECT_EQ(j.get("verified")->type, Json::Type::Bool);
  EXPECT_GE(j.get("passes")->number, 1.0);
  const Json* stages = j.get("stages_ms");
  ASSERT_EQ(stages->object.size(), kStageKeys.size());
  for (std::size_t i = 0; i < kStageKeys.size(); ++i)
    EXPECT_EQ(stages->object[i].first, kStageKeys[i]);
  ASSERT_TRUE(j.get("source_points"));
  EXPECT_EQ(j.get("source_points")->number,
            static_cast<double>(source_.size() - 1)); // one NaN point
  const Json* icp = j.get("icp");
  ASSERT_TRUE(icp);
  ASSERT_NO_FATAL_FAILURE(checkStage(*icp, &truth_, T_icp));
  EXPECT_TRUE(icp->get("converged")->boolean);
  // Everything human-readable went to stderr.
  EXPECT_NE(r.err.find("Registering"), std::string::npos);
}

TEST(ResultKeys, AreTheDocumentedOnes)
{
  // doc/cli.md, "The result's fields": one row per key of visitResultFields(), in
  // order.
  std::ifstream file(std::string(PCL_PHASER_DOC_DIR) + "/cli.md");
  ASSERT_TRUE(file.good()) << "doc/cli.md is missing";
  std::string line;
  while (std::getline(file, line) && line != "### The result's fields") {
  }
  std::vector<std::string> documented;
  std::string stages_row;
  while (std::getline(file, line) && (documented.empty() || !line.empty()))
    if (line.rfind("| `", 0) == 0) {
      documented.push_back(line.substr(3, line.find('`', 3) - 3));
      if (documented.back() == "stages_ms")
        stages_row = line;
    }
  EXPECT_EQ(documented, kResultFieldKeys)
      << "doc/cli.md's table of the result's fields differs from visitResultFields()";
  for (const std::string& stage : kStageKeys)
    EXPECT_NE(stages_row.find("`" + stage + "`"), std::string::npos) << stage;
}

TEST_F(PclPhaserAlign, GroundTruthOnRealScans)
{
  const std::string rel = "lidar/hdl32_fastgicp/";
  PCL_PHASER_REQUIRE_DATA(rel + "251371071.pcd");
  PCL_PHASER_REQUIRE_DATA(rel + "251370668.pcd");
  PCL_PHASER_REQUIRE_DATA(rel + "relative.txt");
  using pcl::phaser::test::dataPath;
  const ToolRun r =
      run(quote(dataPath(rel + "251371071.pcd")) + " " +
          quote(dataPath(rel + "251370668.pcd")) + " --gt " +
          quote(dataPath(rel + "relative.txt")) + " --json --center auto");
  EXPECT_EQ(r.code, 0)
      << r.err; // auto: these LiDAR scans are projected about their origin
  Eigen::Matrix4d truth, T;
  ASSERT_TRUE(pcl::phaser::loadTransform(dataPath(rel + "relative.txt"), truth));
  Json j;
  ASSERT_NO_FATAL_FAILURE(checkJsonRun(r, &truth, j, T));
  EXPECT_LT(j.get("rre_deg")->number, 1.0);
  EXPECT_LT(j.get("rte_m")->number, 0.3);
}

TEST_F(PclPhaserAlign, OutputKeepsEveryFieldAndPoint)
{
  const ToolRun r = run("src.pcd tgt.pcd -o aligned.pcd --json");
  ASSERT_EQ(r.code, 0) << r.err;
  Json j;
  Eigen::Matrix4d T;
  ASSERT_NO_FATAL_FAILURE(checkJsonRun(r, nullptr, j, T));
  pcl::PCLPointCloud2 blob;
  std::string error;
  ASSERT_TRUE(pcl::phaser::loadCloud(path("aligned.pcd"), blob, &error)) << error;
  for (const char* field :
       {"x", "y", "z", "intensity", "normal_x", "normal_y", "normal_z", "curvature"})
    EXPECT_TRUE((pcl::getFieldIndex(blob, field) >= 0)) << field;
  pcl::PointCloud<pcl::PointXYZINormal> aligned;
  ASSERT_TRUE(pcl::phaser::loadCloud(path("aligned.pcd"), aligned, &error)) << error;
  ASSERT_EQ(aligned.size(), source_.size());
  EXPECT_TRUE(std::isnan(aligned[0].x)); // the NaN point is kept, still NaN
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  for (std::size_t i = 1; i < source_.size(); i += 97) {
    const Eigen::Vector3d p = source_[i].getVector3fMap().cast<double>();
    const Eigen::Vector3d n = source_[i].getNormalVector3fMap().cast<double>();
    EXPECT_LT((aligned[i].getVector3fMap().cast<double>() -
               (R * p + T.topRightCorner<3, 1>()))
                  .norm(),
              1e-4)
        << i;
    EXPECT_LT((aligned[i].getNormalVector3fMap().cast<double>() - R * n).norm(), 1e-5);
    EXPECT_EQ(aligned[i].intensity, source_[i].intensity);
  }
}

TEST_F(PclPhaserAlign, ReadsPlyAndKittiBin)
{
  ASSERT_TRUE(pcl::phaser::saveCloud(path("src.bin"), source_));
  ASSERT_TRUE(pcl::phaser::saveCloud(path("tgt.ply"), target_));
  const ToolRun r =
      run("src.bin tgt.ply --passes 1 -b 32 -o aligned.ply -m overlay.pcd");
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  pcl::PCLPointCloud2 blob;
  ASSERT_TRUE(pcl::phaser::loadCloud(path("aligned.ply"), blob));
  EXPECT_EQ(blob.width * blob.height, source_.size());
  EXPECT_TRUE((pcl::getFieldIndex(blob, "intensity") >= 0));
}

TEST_F(PclPhaserAlign, BadInputsFailWithAMessage)
{
  writeBadInputFiles();
  const std::pair<const char*, int> cases[] = {
      {"src.pcd", 1},
      {"src.pcd tgt.pcd extra.pcd", 1},
      {"--demo src.pcd", 1},
      {"src.pcd tgt.pcd --frobnicate", 1},
      {"src.pcd tgt.pcd -b 0", 1},
      {"src.pcd tgt.pcd -b 1000", 1},
      {"src.pcd tgt.pcd --bandwidth abc", 1},
      {"src.pcd tgt.pcd -b", 1},
      {"src.pcd tgt.pcd --gt", 1},
      {"src.pcd tgt.pcd --threads -2", 1},
      {"src.pcd tgt.pcd --threads 65", 1},
      {"src.pcd tgt.pcd --grid 4", 1},
      {"src.pcd tgt.pcd --passes 9", 1},
      {"src.pcd tgt.pcd --center middle", 1},
      {"src.pcd tgt.pcd --center automatic", 1},
      {"src.pcd tgt.pcd --icp-dist -1", 1},
      {"src.pcd tgt.pcd --icp-dist nan", 1},
      {"src.pcd tgt.pcd --size 640", 1},
      {"src.pcd tgt.pcd --size 0x480", 1},
      {"src.pcd tgt.pcd --size axb", 1},
      {"src.pcd tgt.pcd --seed -1", 1},
      {"src.pcd tgt.pcd -o aligned.xyz", 1},
      {"src.pcd tgt.pcd -m overlay.bin", 1},
      {"src.pcd tgt.pcd --screenshot shot.jpg", 1},
      {"missing.pcd tgt.pcd", 2},
      {"src.pcd missing.pcd", 2},
      {"x.xyz tgt.pcd", 2},
      {"garbage.pcd tgt.pcd", 2},
      {"empty.pcd tgt.pcd", 2},
      {"zero.pcd tgt.pcd", 2},
      {"noxyz.pcd tgt.pcd", 2},
      {"nan.pcd tgt.pcd", 2},
      {". tgt.pcd", 2},
      {"src.pcd tgt.pcd --gt missing.txt", 2},
      {"src.pcd tgt.pcd --gt notrigid.txt", 2},
      {"src.pcd tgt.pcd --gt garbage.pcd", 2},
  };
  for (const auto& c : cases) {
    const ToolRun r = run(c.first);
    EXPECT_EQ(r.code, c.second) << "pcl_phaser_align " << c.first << "\n" << r.err;
    EXPECT_FALSE(r.err.empty()) << "no message for: " << c.first;
  }
  for (const char* file : {"no_fields.pcd", "lying_points.pcd", "grid_too_small.ply",
                           "indented_obj_info.ply", "blue_before_red.ply",
                           "range_grid_357913941.ply", "range_grid_357913942.ply"}) {
    for (const std::string& args :
         {std::string(file) + " tgt.pcd", "src.pcd " + std::string(file)}) {
      const ToolRun r = run(args);
      EXPECT_EQ(r.code, 2) << "pcl_phaser_align " << args << "\n" << r.err;
      EXPECT_NE(r.err.find(file), std::string::npos) << args << "\n" << r.err;
    }
  }
}

TEST_F(PclPhaserAlign, JsonReportsErrorsToo)
{
  const ToolRun r = run("missing.pcd tgt.pcd --json");
  EXPECT_EQ(r.code, 2);
  Json j;
  ASSERT_TRUE(JsonReader(r.out).document(j)) << r.out;
  ASSERT_TRUE(j.get("error") && j.get("error")->type == Json::Type::String);
  ASSERT_TRUE(j.get("exit_code"));
  EXPECT_NE(j.get("error")->string.find("missing.pcd"), std::string::npos);
  EXPECT_EQ(j.get("exit_code")->number, 2.0);
  EXPECT_NE(r.err.find("missing.pcd"), std::string::npos);
}

TEST_F(PclPhaserAlign, FailedRegistrationExitsThreeAndStillReports)
{
  pcl::PointCloud<pcl::PointXYZ> origin;
  origin.resize(50, pcl::PointXYZ(0.0f, 0.0f, 0.0f)); // no direction to project
  ASSERT_TRUE(pcl::phaser::saveCloud(path("origin.pcd"), origin));
  const ToolRun r = run("origin.pcd tgt.pcd --json -o never.pcd");
  EXPECT_EQ(r.code, 3) << r.err;
  Json j;
  Eigen::Matrix4d T;
  ASSERT_NO_FATAL_FAILURE(checkJsonRun(r, nullptr, j, T));
  EXPECT_FALSE(j.get("converged")->boolean);
  EXPECT_FALSE(fs::exists(path("never.pcd")));
  EXPECT_NE(r.err.find("did not converge"), std::string::npos) << r.err;
}

TEST_F(PclPhaserAlign, ScreenshotWithoutDisplayFailsCleanly)
{
  const ToolRun r = run("src.pcd tgt.pcd --screenshot shot.png", "env -u DISPLAY ");
  EXPECT_EQ(r.code, 5) << r.err;
  EXPECT_TRUE(r.err.find("DISPLAY") != std::string::npos ||
              r.err.find("visualization") != std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(path("shot.png")));
}

TEST_F(PclPhaserAlign, ScreenshotUnderXvfbHasTheRequestedSize)
{
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "xvfb-run is not installed (apt-get install -y xvfb xauth)";
  const ToolRun r =
      run("src.pcd tgt.pcd --passes 1 --screenshot shot.png --size 640x480",
          "xvfb-run -a -s \"-screen 0 1280x1024x24\" ");
  if (r.code == 5 && r.err.find("without pcl_visualization") != std::string::npos)
    GTEST_SKIP() << "pcl_phaser_align was built without pcl_visualization";
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const std::string png = readFile(path("shot.png"));
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  const auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 4; ++k)
      v = (v << 8) | static_cast<unsigned char>(png[at + k]);
    return (v);
  };
  EXPECT_EQ(be32(16), 640u);
  EXPECT_EQ(be32(20), 480u);
}

} // namespace
