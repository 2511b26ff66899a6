/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "channels/surface_orientation.h"
#include "index/point_index.h"
#include "sphere/spherical_sampling.h"
#include "support/error.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace pcl::phaser {

SurfacePatches surfacePatches(const Eigen::Matrix3Xd& points, double voxel_size,
                              const Eigen::Vector3d& viewpoint, int min_points)
{
  const VoxelGroups groups = groupByVoxel(points, voxel_size);
  SurfacePatches out;
  out.voxel_size = voxel_size;
  out.normals.resize(3, groups.size());
  out.weights.resize(groups.size());
  Eigen::Index count = 0;
  std::vector<double> thickness;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const Eigen::Index begin = groups.offsets[g], end = groups.offsets[g + 1];
    if (end - begin < std::max(min_points, 3))
      continue;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (Eigen::Index k = begin; k < end; ++k)
      mean += points.col(groups.order[k]);
    mean /= static_cast<double>(end - begin);
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (Eigen::Index k = begin; k < end; ++k) {
      const Eigen::Vector3d d = points.col(groups.order[k]) - mean;
      cov += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    const Eigen::Vector3d l = eig.eigenvalues(); // increasing
    if (!(l[2] > 0.0))
      continue;
    Eigen::Vector3d n = eig.eigenvectors().col(0);
    if (n.dot(viewpoint - mean) < 0.0)
      n = -n;
    out.normals.col(count) = n;
    out.keys.push_back(groups.keys[g]);
    thickness.push_back(
        std::sqrt(std::max(0.0, l[0]) / static_cast<double>(end - begin)));
    out.weights[count++] = std::max(0.0, (l[1] - l[0]) / l[2]);
  }
  out.normals.conservativeResize(3, count);
  out.weights.conservativeResize(count);
  if (!thickness.empty()) {
    std::nth_element(thickness.begin(), thickness.begin() + thickness.size() / 2,
                     thickness.end());
    out.thickness = thickness[thickness.size() / 2];
  }
  return out;
}

SphericalSpectrum orientationSpectrum(const SurfacePatches& patches, int bandwidth,
                                      int num_threads)
{
  const auto sht = SphericalHarmonicTransform::instance(bandwidth);
  const std::vector<int> cells = sphereCells(patches.normals, bandwidth, num_threads);
  std::vector<double> histogram(4 * static_cast<std::size_t>(bandwidth) * bandwidth,
                                0.0);
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (cells[i] >= 0)
      histogram[cells[i]] += patches.weights[static_cast<Eigen::Index>(i)];
  // Density per unit solid angle (cells shrink as sin(theta) towards the poles).
  const int rows = 2 * bandwidth;
  double mean = 0.0;
  for (int j = 0; j < rows; ++j) {
    const double area = std::sin(M_PI * (2 * j + 1) / (4.0 * bandwidth));
    for (int k = 0; k < rows; ++k) {
      double& h = histogram[static_cast<std::size_t>(j) * rows + k];
      h = std::sqrt(h / area);
      mean += h;
    }
  }
  mean /= static_cast<double>(histogram.size());
  for (double& h : histogram)
    h -= mean;
  SphericalSpectrum F = sht->forward(histogram.data(), num_threads);
  // A Gaussian low-pass of about two cells: the histogram is a sum of spikes.
  const double sigma = 2.0 * M_PI / (2.0 * bandwidth);
  for (int l = 0; l < bandwidth; ++l)
    F.row(l) *= std::exp(-0.5 * l * (l + 1) * sigma * sigma);
  return F;
}

Eigen::Matrix3Xd patchNormalsAt(const SurfacePatches& patches,
                                const Eigen::Matrix3Xd& points)
{
  std::unordered_map<std::int64_t, Eigen::Index> patch_of;
  for (std::size_t i = 0; i < patches.keys.size(); ++i)
    patch_of.emplace(patches.keys[i], static_cast<Eigen::Index>(i));
  Eigen::Matrix3Xd normals = Eigen::Matrix3Xd::Zero(3, points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    std::int64_t key = 0;
    if (patches.voxel_size > 0.0 && voxelKey(points.col(i), patches.voxel_size, key)) {
      const auto it = patch_of.find(key);
      if (it != patch_of.end())
        normals.col(i) = patches.normals.col(it->second);
    }
  }
  return normals;
}

Eigen::VectorXd orientationWeights(const SurfacePatches& patches,
                                   const Eigen::Matrix3Xd& samples)
{
  constexpr int kBandwidth = 4;
  constexpr int kUnstructured = 4 * kBandwidth * kBandwidth;
  const Eigen::Matrix3Xd normals = patchNormalsAt(patches, samples);
  const std::vector<int> cells = sphereCells(normals, kBandwidth);
  std::vector<int> sample_cell(static_cast<std::size_t>(samples.cols()), kUnstructured);
  std::vector<double> count(kUnstructured + 1, 0.0);
  for (Eigen::Index i = 0; i < samples.cols(); ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    if (cells[k] >= 0)
      sample_cell[k] = cells[k];
    count[sample_cell[k]] += 1.0;
  }
  Eigen::VectorXd w(samples.cols());
  for (Eigen::Index i = 0; i < samples.cols(); ++i)
    w[i] = 1.0 / std::max(count[sample_cell[static_cast<std::size_t>(i)]],
                          0.02 * static_cast<double>(samples.cols()));
  const double sum = w.sum();
  if (sum > 0.0)
    w /= sum;
  return w;
}

} // namespace pcl::phaser
