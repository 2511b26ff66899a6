/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_engine_benchmark: times the rotation engine (SHT, SO(3) correlation with 1
 * and 2 threads, Newton refinement) for a list of bandwidths and reports the peak
 * memory of a process that runs one bandwidth. Each bandwidth runs in a forked child so
 * the peak RSS belongs to that bandwidth alone.
 *
 *   pcl_phaser_engine_benchmark [B ...]        (default: 16 32 64 128)
 */
#include "so3/so3_correlation.h"
#include "so3/so3_refinement.h"
#include "sphere/spherical_grid.h"
#include "sphere/spherical_harmonics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

using namespace pcl::phaser;

namespace {

/** Median wall time in ms of \a reps runs of \a f (after one warm-up run). */
double medianMs(int reps, const std::function<void()>& f)
{
  f();
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    const auto start = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::milli>(
                    std::chrono::steady_clock::now() - start)
                    .count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

/** A smooth random test signal: 12 lobes on the sphere, and the same lobes rotated. */
std::vector<double> lobes(int B, const Eigen::Matrix3d& R)
{
  std::mt19937 rng(1);
  std::normal_distribution<double> n01;
  std::vector<Eigen::Vector3d> dirs;
  for (int i = 0; i < 12; ++i)
    dirs.push_back(R * Eigen::Vector3d(n01(rng), n01(rng), n01(rng)).normalized());
  const int n = 2 * B;
  std::vector<double> f(static_cast<std::size_t>(n) * n);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d w = sampleDirection(j, k, B);
      double v = 0.0;
      for (const auto& d : dirs)
        v += std::exp(0.6 * B * (w.dot(d) - 1.0));
      f[j * n + k] = v;
    }
  return f;
}

void runBandwidth(int B)
{
  const int reps = B >= 128 ? 3 : 7;
  const Eigen::Matrix3d R = rotationFromEuler({0.4, 1.1, -2.0});
  const std::vector<double> target = lobes(B, R);
  const std::vector<double> source = lobes(B, Eigen::Matrix3d::Identity());
  const auto sht = SphericalHarmonicTransform::instance(B);
  const auto corr = So3Correlator::instance(B);
  SphericalSpectrum F, H;
  const double t_sht = medianMs(reps, [&] { F = sht->forward(target.data(), 1); });
  H = sht->forward(source.data(), 1);
  So3GridIndex peak;
  const double t1 = medianMs(reps, [&] { peak = corr->correlate(F, H, 1).argmax(); });
  const double t2 = medianMs(reps, [&] { peak = corr->correlate(F, H, 2).argmax(); });
  const Eigen::Matrix3d start = rotationFromEuler(gridEuler(peak, B));
  RefinedRotation refined;
  const double tr1 =
      medianMs(reps, [&] { refined = refineRotation(F, H, start, B, 3, 1); });
  const double tr2 =
      medianMs(reps, [&] { refined = refineRotation(F, H, start, B, 3, 2); });
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf(
      "| %3d | %8.2f | %9.1f | %9.1f | %8.1f | %8.1f | %7.1f | %9.4f | %9.5f |\n", B,
      t_sht, t1, t2, tr1, tr2, usage.ru_maxrss / 1024.0,
      rotationDistance(start, R) * 180 / M_PI,
      rotationDistance(refined.rotation, R) * 180 / M_PI);
  std::fflush(stdout);
}

} // namespace

int main(int argc, char** argv)
{
  std::vector<int> bandwidths;
  for (int i = 1; i < argc; ++i)
    bandwidths.push_back(std::atoi(argv[i]));
  if (bandwidths.empty())
    bandwidths = {16, 32, 64, 128};
  for (int B : bandwidths)
    if (B < 1 || B > 256) {
      std::fprintf(stderr, "error: bandwidth must be in [1, 256], got %d\n", B);
      return 1;
    }
  std::printf(
      "| B | SHT ms (1 thr) | SO(3) corr ms, 1 thr | 2 thr | refine ms, 1 thr | 2 thr "
      "| peak RSS MB | grid err deg | refined err deg |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  for (int B : bandwidths) {
    const pid_t pid = fork();
    if (pid == 0) {
      runBandwidth(B);
      std::_Exit(0);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::fprintf(stderr, "error: bandwidth %d failed\n", B);
      return 1;
    }
  }
  return 0;
}
