/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "protocol.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace pcl::phaser {
namespace bench {

double rreDeg(const Eigen::Matrix4d& estimate, const Eigen::Matrix4d& truth)
{
  const Eigen::Matrix3d delta =
      estimate.topLeftCorner<3, 3>().transpose() * truth.topLeftCorner<3, 3>();
  const double c = std::clamp((delta.trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(c) * 180.0 / M_PI;
}

double rteM(const Eigen::Matrix4d& estimate, const Eigen::Matrix4d& truth)
{
  return (estimate.topRightCorner<3, 1>() - truth.topRightCorner<3, 1>()).norm();
}

Eigen::Matrix4d randomPose(std::mt19937& rng, double t_max, double max_tilt)
{
  std::normal_distribution<double> n01;
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  if (max_tilt < M_PI) {
    const double yaw = 2.0 * M_PI * u01(rng), azimuth = 2.0 * M_PI * u01(rng);
    const double tilt = std::acos(1.0 - u01(rng) * (1.0 - std::cos(max_tilt)));
    T.topLeftCorner<3, 3>() =
        (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(tilt,
                           Eigen::Vector3d(std::cos(azimuth), std::sin(azimuth), 0.0)))
            .toRotationMatrix();
  } else {
    T.topLeftCorner<3, 3>() = Eigen::Quaterniond(n01(rng), n01(rng), n01(rng), n01(rng))
                                  .normalized()
                                  .toRotationMatrix();
  }
  const Eigen::Vector3d direction =
      Eigen::Vector3d(n01(rng), n01(rng), n01(rng)).normalized();
  T.topRightCorner<3, 1>() = direction * t_max * std::cbrt(u01(rng));
  return T;
}

std::string Condition::sweep() const
{
  switch (kind) {
  case Kind::Noise:
    return "noise";
  case Kind::Sparsity:
    return "sparsity";
  case Kind::Overlap:
    return "overlap";
  default:
    return "clean";
  }
}

std::string Condition::label() const
{
  char text[64];
  switch (kind) {
  case Kind::Noise:
    std::snprintf(text, sizeof(text), "PSNR %g dB", value);
    break;
  case Kind::Sparsity:
    std::snprintf(text, sizeof(text), "keep %g %%", value * 100.0);
    break;
  case Kind::Overlap:
    std::snprintf(text, sizeof(text), "overlap %g %%", value * 100.0);
    break;
  default:
    return "clean";
  }
  return text;
}

bool parseCondition(const std::string& text, Condition& condition)
{
  if (text == "clean") {
    condition = Condition{};
    return true;
  }
  const auto colon = text.find(':');
  if (colon == std::string::npos)
    return false;
  const std::string kind = text.substr(0, colon);
  char* end = nullptr;
  const std::string number = text.substr(colon + 1);
  const double value = std::strtod(number.c_str(), &end);
  if (number.empty() || *end != '\0' || !std::isfinite(value))
    return false;
  if (kind == "noise" && value > 0.0 && value < 200.0)
    condition = {Condition::Kind::Noise, value};
  else if (kind == "sparsity" && value > 0.0 && value <= 1.0)
    condition = {Condition::Kind::Sparsity, value};
  else if (kind == "overlap" && value > 0.0 && value <= 1.0)
    condition = {Condition::Kind::Overlap, value};
  else
    return false;
  return true;
}

namespace {

void addNoise(double psnr_db, Cloud& cloud, std::mt19937& rng)
{
  double r_max = 0.0, i_max = 0.0;
  for (const auto& p : cloud) {
    r_max = std::max(r_max, static_cast<double>(p.getVector3fMap().norm()));
    i_max = std::max(i_max, static_cast<double>(std::abs(p.intensity)));
  }
  const double attenuation = std::pow(10.0, psnr_db / 20.0);
  std::normal_distribution<float> xyz(0.0f, static_cast<float>(r_max / attenuation));
  std::normal_distribution<float> intensity(0.0f,
                                            static_cast<float>(i_max / attenuation));
  for (auto& p : cloud) {
    p.x += xyz(rng);
    p.y += xyz(rng);
    p.z += xyz(rng);
    p.intensity += intensity(rng);
  }
}

template <typename Keep>
void keepIf(Cloud& cloud, Keep keep)
{
  Cloud kept;
  kept.reserve(cloud.size());
  for (const auto& p : cloud)
    if (keep(p))
      kept.push_back(p);
  kept.header = cloud.header;
  kept.sensor_origin_ = cloud.sensor_origin_;
  kept.sensor_orientation_ = cloud.sensor_orientation_;
  cloud = std::move(kept);
}

} // namespace

void keepSector(Cloud& cloud, double center, double half_width)
{
  keepIf(cloud, [&](const PointT& p) {
    const double d = std::remainder(std::atan2(p.y, p.x) - center, 2.0 * M_PI);
    return std::abs(d) <= half_width;
  });
}

void applyCondition(const Condition& condition, Cloud& cloud, std::mt19937& rng)
{
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  switch (condition.kind) {
  case Condition::Kind::Noise:
    addNoise(condition.value, cloud, rng);
    break;
  case Condition::Kind::Sparsity:
    keepIf(cloud, [&](const PointT&) { return u01(rng) < condition.value; });
    break;
  case Condition::Kind::Overlap: {
    const double center = (2.0 * u01(rng) - 1.0) * M_PI;
    keepSector(cloud, center, condition.value * M_PI);
    break;
  }
  default:
    break;
  }
}

} // namespace bench
} // namespace pcl::phaser
