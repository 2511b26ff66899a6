// SPDX-License-Identifier: BSD-3-Clause
// Copyright (c) 2026, the pcl_phaser developers.
//
#include "batch_cache.h"
#include "batch_progress.h"
#include "batch_records.h"
#include "batch_runner.h"

#include <pcl_phaser/core/warm_up.h>

#include <pcl/console/print.h>

#include <chrono>
#include <csignal>
#include <map>
#include <thread>
#include <unistd.h>

namespace pcl {
namespace phaser {
namespace batch {
namespace {

volatile std::sig_atomic_t stop_requested = 0;

void requestStop(int)
{
  stop_requested = 1;
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
 *  a pair of this shard (another list, another shard: use another --out). */
std::string pendingPairs(const PairList& list, const std::vector<std::size_t>& shard,
                         const std::vector<Record>& records, const std::string& out,
                         std::vector<std::size_t>& pending)
{
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
    done[it->second] = true;
  }
  pending.clear();
  for (const std::size_t i : shard)
    if (!done[i])
      pending.push_back(i);
  return {};
}

/** \brief Align one pair (loading what the cache lacks) into its record; nothing when
 *  a stop signal cut a load short (the pair is redone on resume). */
std::optional<Record> alignPair(const Pair& pair, std::size_t pairs, CloudCache& cache,
                                const PhaserParameters& params)
{
  std::string error;
  const std::shared_ptr<CloudEntry> target = cache.get(pair.target_path, error);
  const std::shared_ptr<CloudEntry> source =
      target ? cache.get(pair.source_path, error) : nullptr;
  if (!target || !source) {
    if (stop_requested)
      return std::nullopt;
    return failedRecord(pair, pairs, error);
  }
  const auto start = std::chrono::steady_clock::now();
  const AlignOutcome outcome = alignEntries(*source, *target, pair.guess, params);
  const double ms = std::chrono::duration<double, std::milli>(
                        std::chrono::steady_clock::now() - start)
                        .count();
  return alignedRecord(pair, pairs, outcome.result, outcome.covariance, ms);
}

/** \brief The engine's first align of a process touches its memory anew (most of what
 *  it costs beyond the next fresh align: doc/benchmarks.md): warm it up on a thread
 *  while the first pair is read, and keep the memory of one align for the next. */
std::thread startWarmUp(const PhaserParameters& params)
{
  WarmUpOptions options;
  options.keep_memory = true;
  return std::thread([params, options] { warmUp(params, options); });
}

/** \brief Read the first pair's clouds, then wait for the warm-up. */
void finishWarmUp(std::thread& warm_up, const Pair& first, CloudCache& cache)
{
  std::string ignored; // a load that fails is reported with its pair
  cache.get(first.target_path, ignored);
  cache.get(first.source_path, ignored);
  warm_up.join();
}

int writeGraph(const RunSettings& settings, const PairList& list)
{
  if (settings.g2o.empty())
    return kOk;
  std::vector<Record> records;
  std::string error = readRecords(settings.out, records, false);
  if (error.empty())
    error = writeFileAtomically(settings.g2o, g2oGraph(records, list.poses));
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
  if (std::string error = pendingPairs(list, shard, records, settings.out, pending);
      !error.empty())
    return failWith(kInput, error);
  if (!settings.g2o.empty() && ::access(folderOf(settings.g2o).c_str(), W_OK) != 0)
    return failWith(kOutput, "cannot write '" + settings.g2o +
                                 "': its folder is not "
                                 "writable");
  RecordWriter writer;
  if (std::string error = writer.open(settings.out); !error.empty())
    return failWith(kOutput, error);
  catchStopSignals();
  CloudCache cache(static_cast<std::size_t>(settings.cache));
  Progress progress(shard.size(), shard.size() - pending.size(),
                    countAccepted(records));
  std::thread warm_up = pending.empty() ? std::thread() : startWarmUp(settings.params);
  for (const std::size_t i : pending) {
    if (warm_up.joinable())
      finishWarmUp(warm_up, list.pairs[i], cache);
    if (stop_requested)
      break;
    const std::optional<Record> record =
        alignPair(list.pairs[i], list.pairs.size(), cache, settings.params);
    if (!record)
      break;
    if (std::string error = writer.append(*record); !error.empty())
      return failWith(kOutput, error);
    progress.finished(list.pairs[i], *record);
  }
  progress.close();
  const int graph = writeGraph(settings, list);
  if (stop_requested) {
    pcl::console::print_warn("Stopped: %zu of %zu pairs of this shard are recorded in "
                             "'%s'; run the same command again to resume.\n",
                             progress.done(), shard.size(), settings.out.c_str());
    return kInterrupted;
  }
  return graph;
}

} // namespace batch
} // namespace phaser
} // namespace pcl
