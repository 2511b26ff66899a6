/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "support/parallel.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace pcl::phaser::detail {

namespace {

/** How long a thread out of work polls before it blocks: most serial steps between
 *  an align's loops are shorter, and a time slice is much longer. */
constexpr std::chrono::microseconds kPoll(50);

/** Polls \a ready for up to kPoll; whether it became true. */
template <typename Ready>
bool poll(const Ready& ready)
{
  const auto until = std::chrono::steady_clock::now() + kPoll;
  do {
    for (int i = 0; i < 64; ++i)
      if (ready())
        return true;
  } while (std::chrono::steady_clock::now() < until);
  return false;
}

/** One call of parallelFor: its chunks go to whoever asks first. Workers arriving after
 *  it ended find no chunk and never touch the body (on the caller's stack). */
struct Job {
  const ChunkBody* body = nullptr;
  std::ptrdiff_t count = 0, chunk = 0, chunks = 0;
  int threads = 1;
  std::atomic<std::ptrdiff_t> next{0};
  std::atomic<std::ptrdiff_t> ended{0};
  std::atomic<int> slots{1}; // the caller is slot 0
  std::atomic<bool> failed{false};
  std::mutex mutex;
  std::condition_variable all_ended;
  bool finished = false;    // guarded by mutex
  std::exception_ptr error; // guarded by mutex

  /** Takes chunks until none is left. */
  void work(int slot)
  {
    for (;;) {
      const std::ptrdiff_t k = next.fetch_add(1);
      if (k >= chunks)
        return;
      if (!failed.load()) {
        try {
          (*body)(k * chunk, std::min(count, (k + 1) * chunk), slot);
        } catch (...) {
          std::lock_guard<std::mutex> lock(mutex);
          if (!error)
            error = std::current_exception();
          failed = true;
        }
      }
      if (ended.fetch_add(1) + 1 == chunks) {
        std::lock_guard<std::mutex> lock(mutex);
        finished = true;
        all_ended.notify_all();
      }
    }
  }
};

/** Worker threads, started when first needed and kept; they sleep between jobs. */
class Pool {
public:
  ~Pool()
  {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_)
      t.join();
  }

  /** Invites up to \a helpers workers to \a job. */
  void invite(const std::shared_ptr<Job>& job, int helpers)
  {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      while (static_cast<int>(threads_.size()) < helpers) {
        try {
          threads_.emplace_back([this] { run(); });
        } catch (const std::system_error&) {
          break; // no more threads: the caller does the rest
        }
      }
      helpers = std::min(helpers, static_cast<int>(threads_.size()));
      for (int i = 0; i < helpers; ++i)
        queue_.push_back(job);
      queued_ += helpers;
    }
    for (int i = 0; i < helpers; ++i)
      wake_.notify_one();
  }

private:
  void run()
  {
    for (;;) {
      std::shared_ptr<Job> job;
      poll([this] { return queued_.load(std::memory_order_relaxed) > 0; });
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
        if (stop_)
          return;
        job = std::move(queue_.front());
        queue_.pop_front();
        --queued_;
      }
      const int slot = job->slots.fetch_add(1);
      if (slot < job->threads)
        job->work(slot);
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::shared_ptr<Job>> queue_;
  std::atomic<int> queued_{0}; ///< queue_.size(), read without the lock while polling
  std::vector<std::thread> threads_;
  bool stop_ = false;
};

Pool& pool()
{
  static Pool instance;
  return instance;
}

} // namespace

void parallelFor(std::ptrdiff_t count, std::ptrdiff_t chunk, int threads,
                 const ChunkBody& body)
{
  if (count <= 0)
    return;
  chunk = std::max<std::ptrdiff_t>(chunk, 1);
  const std::ptrdiff_t chunks = (count + chunk - 1) / chunk;
  if (threads <= 1 || chunks == 1) {
    for (std::ptrdiff_t first = 0; first < count; first += chunk)
      body(first, std::min(count, first + chunk), 0);
    return;
  }
  auto job = std::make_shared<Job>();
  job->body = &body;
  job->count = count;
  job->chunk = chunk;
  job->chunks = chunks;
  job->threads = threads;
  pool().invite(job,
                static_cast<int>(std::min<std::ptrdiff_t>(threads - 1, chunks - 1)));
  job->work(0);
  poll([&] { return job->ended.load() == job->chunks; });
  std::unique_lock<std::mutex> lock(job->mutex);
  job->all_ended.wait(lock, [&] { return job->finished; });
  if (job->error)
    std::rethrow_exception(job->error);
}

} // namespace pcl::phaser::detail
