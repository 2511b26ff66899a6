// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
#include "batch_progress.h"

#include <cstdio>
#include <string>
#include <sys/resource.h>
#include <unistd.h>

namespace pcl {
namespace phaser {
namespace batch {
namespace {

/** Minor page faults of the whole process (every thread) so far. */
long minorFaults()
{
  rusage usage{};
  return ::getrusage(RUSAGE_SELF, &usage) == 0 ? usage.ru_minflt : 0;
}

std::string duration(double seconds)
{
  const long s = static_cast<long>(seconds + 0.5);
  char buffer[32];
  if (s >= 3600)
    std::snprintf(buffer, sizeof(buffer), "%ldh%02ldm", s / 3600, s / 60 % 60);
  else
    std::snprintf(buffer, sizeof(buffer), "%ldm%02lds", s / 60, s % 60);
  return buffer;
}

} // namespace

std::size_t countAccepted(const std::vector<Record>& records)
{
  std::size_t n = 0;
  for (const Record& r : records)
    n += r.value("converged", false) ? 1 : 0;
  return n;
}

Progress::Progress(std::size_t total, std::size_t done, std::size_t accepted)
    : total_(total)
    , done_(done)
    , accepted_(accepted)
    , resumed_(done)
    , terminal_(::isatty(STDERR_FILENO) == 1)
    , start_(std::chrono::steady_clock::now())
    , start_faults_(minorFaults())
{
  if (done > 0)
    std::fprintf(stderr, "Resuming: %zu of %zu pairs already recorded.\n", done, total);
}

void Progress::finished(const Pair& pair, const Record& record)
{
  ++done_;
  const bool failed = record.value("status", "") != "ok";
  failed_ += failed ? 1 : 0;
  accepted_ += record.value("converged", false) ? 1 : 0;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = static_cast<double>(done_ - resumed_) / std::max(seconds, 1e-9);
  const std::string eta = duration(static_cast<double>(total_ - done_) / rate);
  char line[256];
  std::snprintf(line, sizeof(line),
                "%zu/%zu pairs, %.2f pairs/s, ETA %s, %zu accepted, %zu failed", done_,
                total_, rate, eta.c_str(), accepted_, failed_);
  if (terminal_)
    std::fprintf(stderr, "\r\033[K%s", line);
  else
    std::fprintf(stderr, "%s | %s -> %s: %s\n", line, pair.source.c_str(),
                 pair.target.c_str(),
                 failed ? record.value("error", "failed").c_str()
                 : record.value("converged", false) ? "converged"
                                                    : "not converged");
  std::fflush(stderr);
}

void Progress::close()
{
  if (terminal_ && done_ > resumed_)
    std::fprintf(stderr, "\n");
  const std::size_t pairs = done_ - resumed_;
  if (pairs == 0)
    return;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stderr,
               "%zu pairs in %.1f s: %.0f ms and %ld minor page faults a pair\n", pairs,
               seconds, 1000.0 * seconds / static_cast<double>(pairs),
               (minorFaults() - start_faults_) / static_cast<long>(pairs));
}

} // namespace batch
} // namespace phaser
} // namespace pcl
