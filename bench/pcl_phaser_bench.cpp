/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * pcl_phaser_bench: the benchmark, calibration and speed programs of bench/ as one
 * harness, `pcl_phaser_bench SUBCOMMAND [options]`, every option `--kebab-case` and the
 * engine's settings spelled as pcl_phaser_align spells them (doc/benchmarks.md).
 */
#include "cloud_reading.h"
#include "fft_yardstick.h"
#include "subcommands.h"

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

using namespace pcl::phaser::bench;

/** Prints the yardstick in ms (bench/loop_closures.sh measures it around its runs). */
int printYardstick(BenchArguments&)
{
  return std::printf("%.3f\n", fftYardstickMs()) < 0;
}

const std::vector<Subcommand>& subcommands()
{
  static const std::vector<Subcommand> all = {
      kCompare,     kNees,  kDetection, kRevisits, kObjects,
      kAlign,       kSpeed, kPriorMap,  kRegion,   kCalibrateCovariance,
#ifdef PCL_PHASER_BENCH_LOOP_CLOSURE
      kLoopClosure,
#endif
      kYardstick};
  return all;
}

void printUsage(std::FILE* out)
{
  std::fprintf(out, "Usage: pcl_phaser_bench SUBCOMMAND [options]  (SUBCOMMAND --help: "
                    "its options)\n\nSubcommands:\n");
  for (const Subcommand& s : subcommands())
    std::fprintf(out, "  %-21s %s\n", s.name, s.summary);
}

} // namespace

const Subcommand pcl::phaser::bench::kYardstick = {
    "yardstick",   "the time (ms) of one 128^3 r2c FFT on one thread",
    nullptr,       {},
    false,         0,
    printYardstick};

int main(int argc, char** argv)
{
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    printUsage(argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  for (const Subcommand& s : subcommands()) {
    if (std::strcmp(argv[1], s.name))
      continue;
    for (int i = 2; i < argc; ++i)
      if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h"))
        return printSubcommandHelp(s), 0;
    std::string command = "pcl_phaser_bench";
    for (int i = 1; i < argc; ++i)
      command += std::string(" ") + argv[i];
    BenchArguments args(argc - 1, argv + 1, s, command);
    // Clouds are read from a reader process started while this one is small. Else each
    // read forks this process, and the next align pays copy-on-write faults on the
    // memory it reuses (revisits: 12-15k instead of 0.1-5k, 1.5x its time).
    pcl::phaser::startCloudReader();
    return args.ok() ? s.run(args) : args.fail();
  }
  std::fprintf(stderr, "pcl_phaser_bench: unknown subcommand '%s'\n\n", argv[1]);
  printUsage(stderr);
  return 2;
}
