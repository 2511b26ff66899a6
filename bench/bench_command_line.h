/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
/** \file bench_command_line.h
 * \brief The command line of one pcl_phaser_bench subcommand: its `--kebab-case`
 * options from a table (the shared ones, --data, --pairs-file, --csv, ..., spelled and
 * documented once in kSharedOptions), the engine's settings as the tools take them
 * (tools/engine_options.h), typed reads that record the first problem, and the help.
 */
#pragma once

#include "engine_options.h"

#include <pcl_phaser/core/parameters.h>

#include <string>
#include <vector>

namespace pcl::phaser {
namespace bench {

/** \brief One option of a subcommand: its name, its value in the help (null: a
 *  switch) and its help text (null: the shared option's, see sharedOption()). */
struct BenchOption {
  const char* name;
  const char* value = nullptr;
  const char* help = nullptr;
};

/** \brief The row of kSharedOptions named \a name, for a subcommand's table; the
 *  default in its help is the subcommand's, so \a help may replace the text. */
BenchOption sharedOption(const char* name, const char* help = nullptr);

class BenchArguments;

/** \brief A subcommand: its name, one line of summary, the files it takes (null:
 *  none), its options, whether it takes the engine's settings (and its default of
 *  --threads), and its run. */
struct Subcommand {
  const char* name;
  const char* summary;
  const char* files;
  std::vector<BenchOption> options;
  bool engine;
  int threads;
  int (*run)(BenchArguments& args); ///< the exit status
};

/** \brief The arguments of one subcommand, collected by collectArguments(): typed
 *  reads of its options (a malformed value is recorded, the fallback returned) and the
 *  engine's settings. The first problem is kept: ok() false, error() the message. */
class BenchArguments {
public:
  /** \brief Collects \a argv (argv[0] the subcommand's name) against \a sub's options;
   *  \a command is the whole command line, for the reports. */
  BenchArguments(int argc, char** argv, const Subcommand& sub, std::string command);

  /** \brief The subcommand's name. */
  const char* name() const { return sub_.name; }
  /** \brief Whether option \a name was given. */
  bool has(const char* name) const { return line_.count(name) > 0; }
  /** \brief The value of \a name, or \a fallback. */
  std::string text(const char* name, const std::string& fallback = "") const;
  /** \brief The integer value of \a name, or \a fallback. */
  long integer(const char* name, long fallback);
  /** \brief The finite number of \a name, or \a fallback. */
  double number(const char* name, double fallback);
  /** \brief The non-empty comma-separated values of \a name, or \a fallback. */
  std::vector<std::string> list(const char* name,
                                std::vector<std::string> fallback) const;
  /** \brief The comma-separated finite numbers of \a name, or \a fallback. */
  std::vector<double> numbers(const char* name, std::vector<double> fallback);
  /** \brief --data: the shared data directory (default: the one beside the source). */
  std::string data() const { return text("--data", PCL_PHASER_DEFAULT_DATA_DIR); }
  /** \brief The files (arguments that are no option). */
  const std::vector<std::string>& files() const { return line_.files; }
  /** \brief The engine's settings: the defaults with \a threads threads, then the
   *  engine options given, checked by validateParameters(). */
  PhaserParameters engine(int threads);
  /** \brief Records \a message as a problem unless \a ok. \return ok */
  bool check(bool ok, const std::string& message);
  /** \brief Whether no problem was found. */
  bool ok() const { return error_.empty(); }
  /** \brief Prints the problem and a pointer to the help. \return 2 */
  int fail() const;
  /** \brief The whole command line, as given. */
  const std::string& command() const { return command_; }

private:
  const Subcommand& sub_;
  CommandLine line_;
  std::string command_, error_;
};

/** \brief Prints \a sub's help: usage, summary, its options and, when it takes them,
 *  the engine's with their defaults. */
void printSubcommandHelp(const Subcommand& sub);

} // namespace bench
} // namespace pcl::phaser
