/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The C++ library on raw float32 clouds, for the Python module's bit-equality tests:
 *   pcl_phaser_reference_align SOURCE.f32 TARGET.f32 COLUMNS THREADS
 * reads N x COLUMNS (3: x y z as PointXYZ, 4: x y z intensity as PointXYZI) floats,
 * registers with pcl::PhaserRegistration at the defaults and THREADS threads, and
 * prints every figure as a C99 hexadecimal float (exact), one "name values..." line
 * each.
 */
#include <pcl_phaser/phaser_registration.h>

#include <pcl/point_types.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <type_traits>
#include <vector>

namespace {

template <typename PointT>
bool readRaw(const char* path, int columns, pcl::PointCloud<PointT>& cloud)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return false;
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                          std::istreambuf_iterator<char>());
  const std::size_t row = sizeof(float) * static_cast<std::size_t>(columns);
  if (bytes.empty() || bytes.size() % row != 0)
    return false;
  const std::size_t n = bytes.size() / row;
  cloud.resize(n);
  cloud.is_dense = false;
  for (std::size_t i = 0; i < n; ++i) {
    float v[4] = {0, 0, 0, 0};
    std::memcpy(v, bytes.data() + i * row, row);
    cloud[i].x = v[0], cloud[i].y = v[1], cloud[i].z = v[2];
    if constexpr (std::is_same_v<PointT, pcl::PointXYZI>)
      cloud[i].intensity = v[3];
  }
  return true;
}

template <typename Derived>
void print(const char* name, const Eigen::MatrixBase<Derived>& m)
{
  std::printf("%s", name);
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c)
      std::printf(" %a", static_cast<double>(m(r, c)));
  std::printf("\n");
}

void print(const char* name, double v)
{
  std::printf("%s %a\n", name, v);
}

template <typename PointT>
int run(char** argv, int columns)
{
  auto source = pcl::make_shared<pcl::PointCloud<PointT>>();
  auto target = pcl::make_shared<pcl::PointCloud<PointT>>();
  if (!readRaw(argv[1], columns, *source) || !readRaw(argv[2], columns, *target)) {
    std::fprintf(stderr, "cannot read %s or %s as float32 x %d\n", argv[1], argv[2],
                 columns);
    return 2;
  }
  pcl::PhaserRegistration<PointT, PointT> phaser;
  phaser.setNumberOfThreads(static_cast<unsigned>(std::atoi(argv[4])));
  phaser.setInputSource(source);
  phaser.setInputTarget(target);
  pcl::PointCloud<PointT> aligned;
  phaser.align(aligned);
  const pcl::phaser::PhaserResult& r = phaser.getResult();
  const pcl::phaser::Verification& v = r.diagnostics.verification;
  std::printf("error %s\n", r.error.c_str());
  print("transformation", r.transformation);
  print("converged", phaser.hasConverged() ? 1.0 : 0.0);
  print("covariance", phaser.getCovariance());
  print("verification",
        Eigen::Vector<double, 6>(v.inlier_fraction, v.score, v.free_space_violation,
                                 v.reverse_free_space_violation, v.constraint, v.rank));
  print("hypotheses", static_cast<double>(r.diagnostics.hypotheses.size()));
  print("chosen_hypothesis", r.chosen_hypothesis);
  for (const auto& h : r.diagnostics.hypotheses)
    print("hypothesis", h.transformation);
  return 0;
}

} // namespace

int main(int argc, char** argv)
{
  const int columns = argc == 5 ? std::atoi(argv[3]) : 0;
  if (columns == 3)
    return run<pcl::PointXYZ>(argv, columns);
  if (columns == 4)
    return run<pcl::PointXYZI>(argv, columns);
  std::fprintf(stderr, "usage: %s SOURCE.f32 TARGET.f32 3|4 THREADS\n", argv[0]);
  return 1;
}
