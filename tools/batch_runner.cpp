// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
#include "batch_cache.h"
#include "batch_progress.h"
#include "batch_records.h"
#include "batch_runner.h"
#include "engine_options.h"


#include <pcl/console/print.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <unistd.h>

namespace pcl {
namespace phaser {
namespace batch {
namespace {

// Written by the signal handler, read by every job (lock-free, so async-signal-safe).
std::atomic<bool> stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);

void requestStop(int)
{
  stop_requested = true;
}

/** \brief SIGINT and SIGTERM (Slurm's time limit) let the pairs in flight finish. */
void catchStopSignals()
{
  struct sigaction action = {};
  action.sa_handler = requestStop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int failWith(int code, const std::string& reason)
{
  pcl::console::print_error("%s\n", reason.c_str());
  return code;
}

/** \brief The pairs of the shard not yet in \a records; an error when a record is not
 *  a pair of this list, shard and settings (use another --out) or is there twice. */
std::string pendingPairs(const PairList& list, const std::vector<std::size_t>& shard,
                         const std::vector<Record>& records,
                         const RunSettings& settings, std::vector<std::size_t>& pending)
{
  const std::string& out = settings.out;
  const std::string fingerprint =
      runFingerprint(settings.params, settings.shard, settings.shards);
  for (const Record& r : records)
    if (r.value("run", std::string()) != fingerprint ||
        r.value("pairs", std::size_t{0}) != list.pairs.size())
      return "'" + out + "' was written by another run (" +
             r.value("run", std::string("?")) + ", " + r["pairs"].dump() +
             " pairs; this one: " + fingerprint + ", " +
             std::to_string(list.pairs.size()) + " pairs): use another --out";
  std::map<std::string, std::size_t> mine;
  for (const std::size_t i : shard)
    mine.emplace(pairKey(list.pairs[i].source, list.pairs[i].target), i);
  std::vector<bool> done(list.pairs.size(), false);
  for (const Record& r : records) {
    const auto it = mine.find(
        pairKey(r.value("source", std::string()), r.value("target", std::string())));
    if (it == mine.end() || r["pair"].get<std::size_t>() != it->second)
      return "'" + out + "' holds pair " + r["pair"].dump() + " (" +
             r.value("source", std::string()) + " -> " +
             r.value("target", std::string()) +
             "), which is not that pair of this list and shard: use another --out";
    if (done[it->second])
      return "'" + out + "' holds pair " + r["pair"].dump() + " twice";
    done[it->second] = true;
  }
  pending.clear();
  for (const std::size_t i : shard)
    if (!done[i])
      pending.push_back(i);
  return {};
}

/** \brief Loaded clouds kept for all jobs: a scan is the source of many pairs (about
 *  2.5 MB for an 80k-point scan). */
constexpr std::size_t kLoadedClouds = 64;

/** \brief What the jobs of a run share: the work, the clouds, the output. */
struct Run {
  Run(const PairList& pairs, const RunSettings& run_settings)
      : list(pairs)
      , settings(run_settings)
      , params(run_settings.params)
      , fingerprint(runFingerprint(run_settings.params, run_settings.shard,
                                   run_settings.shards))
  {
  }
  const PairList& list;
  const RunSettings& settings;
  PhaserParameters params;                    ///< each job's (threads split)
  std::string fingerprint;                    ///< runFingerprint(), in every record
  std::vector<std::vector<std::size_t>> work; ///< pieces of target groups
  std::atomic<std::size_t> next{0};           ///< the next piece to take
  CloudCache clouds{kLoadedClouds};
  RecordWriter writer;
  std::mutex output; ///< guards writer, progress and error
  std::unique_ptr<Progress> progress;
  std::string error; ///< the first write failure
  std::atomic<bool> failed{false};
};

/** \brief The pending pairs as pieces of consecutive pairs of one target, none longer
 *  than an even share of the jobs (so that one big group still runs on every job). */
std::vector<std::vector<std::size_t>>
workPieces(const PairList& list, const std::vector<std::size_t>& pending, int jobs)
{
  const std::size_t share = std::max<std::size_t>(
      1, (pending.size() + static_cast<std::size_t>(jobs) - 1) / jobs);
  std::vector<std::vector<std::size_t>> pieces;
  for (std::size_t k = 0; k < pending.size(); ++k) {
    const bool same = k > 0 && list.pairs[pending[k]].target_id ==
                                   list.pairs[pending[k - 1]].target_id;
    if (!same || pieces.back().size() >= share)
      pieces.emplace_back();
    pieces.back().push_back(pending[k]);
  }
  return pieces;
}

/** \brief Align one pair (loading what the cache lacks) into its record; nothing when
 *  a stop signal cut a load short (the pair is redone on resume). */
std::optional<Record> alignPair(const Pair& pair, Run& run, PreparedTargets& prepared)
{
  std::string error;
  const auto target = run.clouds.get(pair.target_path, error);
  const auto source = target ? run.clouds.get(pair.source_path, error) : nullptr;
  const std::size_t pairs = run.list.pairs.size();
  if (!target || !source) {
    if (stop_requested)
      return std::nullopt;
    return failedRecord(pair, pairs, error);
  }
  const auto start = std::chrono::steady_clock::now();
  const PhaserResult result =
      alignClouds(*source, pair.target_path, *target, prepared, pair.guess, run.params);
  const double ms = std::chrono::duration<double, std::milli>(
                        std::chrono::steady_clock::now() - start)
                        .count();
  return alignedRecord(pair, pairs, result, ms);
}

/** \brief One job: takes pieces until none is left, a stop is asked or a write
 *  failed, keeping its own prepared targets. */
void runJob(Run& run)
{
  PreparedTargets prepared(static_cast<std::size_t>(run.settings.cache));
  for (std::size_t piece; (piece = run.next++) < run.work.size();)
    for (const std::size_t i : run.work[piece]) {
      if (stop_requested || run.failed)
        return;
      std::optional<Record> record = alignPair(run.list.pairs[i], run, prepared);
      if (!record)
        return;
      (*record)["run"] = run.fingerprint;
      const std::lock_guard<std::mutex> lock(run.output);
      if (run.failed) // another job's write failed: append nothing after it
        return;
      if (std::string error = run.writer.append(*record); !error.empty()) {
        run.error = error;
        run.failed = true;
        return;
      }
      run.progress->finished(run.list.pairs[i], *record);
    }
}

/** \brief Run the work on \a jobs threads (the calling one among them). */
void runJobs(Run& run, int jobs)
{
  std::vector<std::thread> others;
  for (int j = 1; j < jobs; ++j)
    others.emplace_back([&run] { runJob(run); });
  runJob(run);
  for (std::thread& t : others)
    t.join();
}

int writeGraph(const RunSettings& settings, const PairList& list)
{
  if (settings.g2o.empty())
    return kOk;
  std::vector<Record> records;
  std::string error = readRecords(settings.out, records, false);
  if (error.empty())
    error = writeFileAtomically(settings.g2o,
                                g2oGraph(records, list.poses, settings.odometry));
  return error.empty() ? kOk : failWith(kOutput, error);
}

} // namespace

int runBatch(const PairList& list, const RunSettings& settings)
{
  const std::vector<std::size_t> shard =
      shardPairs(list, settings.shard, settings.shards);
  std::vector<Record> records;
  std::vector<std::size_t> pending;
  if (std::string error = readRecords(settings.out, records, true); !error.empty())
    return failWith(kOutput, error);
  if (std::string error = pendingPairs(list, shard, records, settings, pending);
      !error.empty())
    return failWith(kInput, error);
  if (!settings.g2o.empty() && ::access(folderOf(settings.g2o).c_str(), W_OK) != 0)
    return failWith(kOutput,
                    "cannot write '" + settings.g2o + "': its folder is not writable");
  Run run(list, settings);
  if (std::string error = run.writer.open(settings.out); !error.empty())
    return failWith(kOutput, error);
  catchStopSignals();
  const int jobs = std::max(1, settings.jobs);
  if (jobs > 1 && run.params.num_threads == 0)
    run.params.num_threads = std::max(1, resolveThreadCount(0) / jobs);
  run.work = workPieces(list, pending, jobs);
  run.progress = std::make_unique<Progress>(shard.size(), shard.size() - pending.size(),
                                            countAccepted(records));
  runJobs(run, jobs);
  if (run.failed)
    return failWith(kOutput, run.error);
  run.progress->close();
  const int graph = writeGraph(settings, list);
  if (stop_requested && run.progress->done() < shard.size()) {
    pcl::console::print_warn("Stopped: %zu of %zu pairs of this shard are recorded in "
                             "'%s'; run the same command again to resume.\n",
                             run.progress->done(), shard.size(), settings.out.c_str());
    return kInterrupted;
  }
  return graph;
}

} // namespace batch
} // namespace phaser
} // namespace pcl
