/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The parameter table and the messages of bad settings: one table (kParameterRanges)
 * checked by validateParameters and the setters, which refuse at once and keep the
 * previous settings; each message names the field, its value and its range.
 */
#include "registration_test_scene.h"

#include <pcl_phaser/phaser_registration.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

using namespace registration_test;
using pcl::phaser::PhaserParameters;

namespace {

using Phaser = pcl::PhaserRegistration<pcl::PointXYZ, pcl::PointXYZ>;

/** \brief \a p with field \a r set to \a value (rounded for int fields); a region's
 *  field in a region of radius 1 m. */
PhaserParameters with(const pcl::phaser::ParameterRange& r, double value)
{
  PhaserParameters p;
  if (r.in_region)
    p.region = pcl::phaser::Region{0.0, 0.0, 0.0, 1.0};
  r.set(p, value);
  return p;
}

} // namespace

TEST(ParameterTable, DefaultsAndBoundsAreLegalAndBeyondIsRefusedByName)
{
  EXPECT_EQ(pcl::phaser::validateParameters(PhaserParameters()), "");
  for (const pcl::phaser::ParameterRange& r : pcl::phaser::kParameterRanges) {
    SCOPED_TRACE(r.name);
    EXPECT_EQ(pcl::phaser::findParameterRange(r.name), &r);
    EXPECT_GE(r.value(PhaserParameters()), r.min);
    EXPECT_LE(r.value(PhaserParameters()), r.max);
    EXPECT_EQ(pcl::phaser::validateParameters(with(r, r.min)), "");
    if (std::isfinite(r.max)) {
      EXPECT_EQ(pcl::phaser::validateParameters(with(r, r.max)), "");
    }
    if (r.type != pcl::phaser::ParameterType::Integer &&
        r.type != pcl::phaser::ParameterType::Real)
      continue; // bool, enum, flags: below (TypedRowsReadAndWriteTheirNames)
    const double step = r.type == pcl::phaser::ParameterType::Integer ? 1.0 : 0.01;
    std::vector<double> bad = {r.min - step};
    if (std::isfinite(r.max))
      bad.push_back(r.max + step);
    if (r.type == pcl::phaser::ParameterType::Real)
      bad.push_back(std::numeric_limits<double>::quiet_NaN());
    for (const double v : bad) {
      const std::string why = pcl::phaser::validateParameters(with(r, v));
      EXPECT_TRUE(has(why, std::string(r.name) + " = ")) << why;
      EXPECT_TRUE(has(why, "outside its range")) << why;
      EXPECT_TRUE(has(why, r.meaning)) << why;
    }
  }
  EXPECT_EQ(pcl::phaser::findParameterRange("no_such_field"), nullptr);
  // The grid size does not matter, and is not checked, with an explicit voxel size.
  PhaserParameters p;
  p.voxel_size = 0.1;
  p.spatial_grid_size = 0;
  EXPECT_EQ(pcl::phaser::validateParameters(p), "");
  // A region needs a radius; setting the radius to 0 through the table removes it.
  p.region = pcl::phaser::Region{1.0, 2.0, 3.0};
  EXPECT_TRUE(
      has(pcl::phaser::validateParameters(p), "region_radius = 0 with a region"));
  pcl::phaser::findParameterRange("region_radius")->set(p, 0.0);
  EXPECT_FALSE(p.region.has_value());
  pcl::phaser::findParameterRange("region_y")->set(p, 5.0);
  ASSERT_TRUE(p.region.has_value());
  EXPECT_EQ(p.region->y, 5.0);
}

TEST(ParameterMessages, BandwidthOneIsRefusedAndTwoRegisters)
{
  // B = 1 keeps only degree 0, a constant on the sphere: the range starts at 2, and 2
  // runs through on the test scene.
  EXPECT_EQ(pcl::phaser::findParameterRange("bandwidth")->min, 2);
  PhaserParameters p;
  p.bandwidth = 1;
  EXPECT_EQ(pcl::phaser::validateParameters(p),
            "bandwidth = 1 is outside its range 2..256 (" +
                std::string(pcl::phaser::findParameterRange("bandwidth")->meaning) +
                ")");
  const auto scene = makeScene<pcl::PointXYZ>();
  const auto source = seenFrom(*scene, makePose({0, 0, 1}, 0.5, {0.2, 0, 0}));
  Phaser phaser;
  phaser.setBandwidth(2);
  ASSERT_EQ(phaser.getBandwidth(), 2);
  phaser.setInputSource(source);
  phaser.setInputTarget(scene);
  CloudXYZ out;
  phaser.align(out);
  EXPECT_EQ(phaser.getResult().error, "");
}

TEST(ParameterMessages, SettersRefuseAtOnceAndKeepThePreviousSettings)
{
  Phaser phaser;
  phaser.setBandwidth(32);
  testing::internal::CaptureStderr();
  phaser.setBandwidth(1);
  std::string log = testing::internal::GetCapturedStderr();
  EXPECT_EQ(phaser.getBandwidth(), 32);
  EXPECT_TRUE(has(log, "setBandwidth")) << log;
  EXPECT_TRUE(has(log, "bandwidth = 1 is outside its range 2..256")) << log;
  EXPECT_TRUE(has(log, "the previous settings are kept")) << log;

  testing::internal::CaptureStderr();
  phaser.setNumberOfThreads(65);
  log = testing::internal::GetCapturedStderr();
  EXPECT_EQ(phaser.getNumberOfThreads(), 0u);
  EXPECT_TRUE(has(log, "num_threads = 65 is outside its range 0..64")) << log;
  phaser.setNumberOfThreads(3);
  EXPECT_EQ(phaser.getNumberOfThreads(), 3u);
  phaser.setNumberOfThreads(0); // automatic, the default
  EXPECT_EQ(phaser.getNumberOfThreads(), 0u);

  PhaserParameters bad = phaser.getParameters();
  bad.passes = 2;    // legal, but refused with the rest
  bad.whitening = 2; // illegal
  const PhaserParameters given = bad;
  testing::internal::CaptureStderr();
  phaser.setParameters(bad);
  log = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(has(log, "setParameters")) << log;
  EXPECT_TRUE(has(log, "whitening = 2 is outside its range 0..1")) << log;
  EXPECT_EQ(phaser.getParameters().passes, PhaserParameters().passes);
  EXPECT_EQ(phaser.getParameters().whitening, PhaserParameters().whitening);
  EXPECT_EQ(phaser.getBandwidth(), 32);
  EXPECT_EQ(bad.whitening, given.whitening); // the caller's settings are untouched
  EXPECT_EQ(bad.passes, given.passes);
}

TEST(ParameterMessages, EngineStillValidatesAtAlign)
{
  const auto scene = makeScene<pcl::PointXYZ>(1, 2000);
  pcl::phaser::Target target(scene->getMatrixXfMap(3, 4, 0).cast<double>());
  pcl::phaser::SourceCloud source;
  source.points = target.points();
  PhaserParameters p;
  p.orientation_bandwidth = 4;
  const pcl::phaser::PhaserResult r =
      pcl::phaser::align(target, source, Eigen::Matrix4d::Identity(), p);
  EXPECT_TRUE(has(r.error, "orientation_bandwidth = 4 is outside its range 8..128"))
      << r.error;
}

TEST(ParameterTable, TypedRowsReadAndWriteTheirNames)
{
  using pcl::phaser::findParameterRange;
  using pcl::phaser::parameterText;
  using pcl::phaser::parseParameter;
  // Every row's default, min and max read back from their text.
  for (const pcl::phaser::ParameterRange& r : pcl::phaser::kParameterRanges) {
    SCOPED_TRACE(r.name);
    for (const double v : {r.value(PhaserParameters()), r.min, r.max}) {
      double back = -7.0;
      if (std::isfinite(v)) {
        EXPECT_TRUE(parseParameter(r, parameterText(r, v, 17), back));
        EXPECT_EQ(back, v);
      }
    }
  }
  const auto* refine = findParameterRange("normalized_refinement");
  const auto* center = findParameterRange("projection_center");
  const auto* channels = findParameterRange("channels");
  ASSERT_TRUE(refine && center && channels);
  EXPECT_EQ(refine->type, pcl::phaser::ParameterType::Boolean);
  double v = 5.0;
  for (const char* off : {"false", "off", "no", "0"})
    EXPECT_TRUE(parseParameter(*refine, off, v) && v == 0.0) << off;
  for (const char* on : {"true", "on", "yes", "1"})
    EXPECT_TRUE(parseParameter(*refine, on, v) && v == 1.0) << on;
  EXPECT_TRUE(parseParameter(*center, "centroid", v));
  EXPECT_EQ(v, double(pcl::phaser::ProjectionCenter::Centroid));
  EXPECT_FALSE(parseParameter(*center, "sensor_origin", v));
  EXPECT_TRUE(parseParameter(*center, "sensor_origin", v, true)); // Python's spelling
  EXPECT_EQ(parameterText(*center, v), "sensor");
  EXPECT_TRUE(parseParameter(*channels, "range,intensity", v));
  EXPECT_EQ(v, double(pcl::phaser::CHANNEL_RANGE | pcl::phaser::CHANNEL_INTENSITY));
  EXPECT_EQ(parameterText(*channels, v), "range,intensity");
  EXPECT_EQ(parameterText(*channels, channels->value(PhaserParameters())), "all");
  v = 5.0;
  for (const char* bad : {"maybe", "", "True", "2"})
    EXPECT_FALSE(parseParameter(*refine, bad, v)) << bad;
  for (const char* bad : {"bogus", "", "1", "Centroid"})
    EXPECT_FALSE(parseParameter(*center, bad, v)) << bad;
  for (const char* bad : {"range,bogus", "range,", "-1", "4294967296", "x1"})
    EXPECT_FALSE(parseParameter(*channels, bad, v)) << bad;
  for (const char* bad : {"1.5", "64x", "", "1e2"})
    EXPECT_FALSE(parseParameter(*findParameterRange("bandwidth"), bad, v)) << bad;
  EXPECT_EQ(v, 5.0); // unchanged by every refusal
}

TEST(ParameterMessages, AnEnumOutsideItsNamesIsRefused)
{
  PhaserParameters p;
  p.projection_center = static_cast<pcl::phaser::ProjectionCenter>(7);
  const std::string why = pcl::phaser::validateParameters(p);
  EXPECT_TRUE(has(why, "projection_center = 7 is none of sensor, centroid, auto"))
      << why;
  Phaser phaser;
  testing::internal::CaptureStderr();
  phaser.setParameters(p);
  const std::string log = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(has(log, "projection_center = 7 is none of")) << log;
  EXPECT_EQ(phaser.getParameters().projection_center,
            pcl::phaser::ProjectionCenter::Automatic);
}
