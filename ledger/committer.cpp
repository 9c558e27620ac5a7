#include "ledger/committer.h"

#include <algorithm>
#include <cassert>
#include <deque>
#include <utility>

namespace zonesim::ledger {

std::string_view submitName(Submit submit) {
  switch (submit) {
    case Submit::Accepted:
      return "accepted";
    case Submit::Full:
      return "full";
    case Submit::Invalid:
      return "invalid";
    case Submit::Stopped:
      return "stopped";
  }
  return "unknown";
}

LedgerCommitter::LedgerCommitter(std::unique_ptr<LedgerStore> store, CommitterOptions options)
    : store_(std::move(store)),
      options_(options),
      submissions_(std::max<std::size_t>(options.capacity, 1)),
      outcomes_(std::max<std::size_t>(options.capacity, 1)) {
  options_.capacity = std::max<std::size_t>(options_.capacity, 1);
  options_.max_batch = std::max<std::size_t>(options_.max_batch, 1);
  worker_ = std::thread([this] { run(); });
}

LedgerCommitter::~LedgerCommitter() {
  stop();
}

Submit LedgerCommitter::submit(const Transaction& tx) {
  if (stopping_.load(std::memory_order_relaxed)) return Submit::Stopped;
  if (invalidReason(tx)) return Submit::Invalid;
  // in_flight_ counts what sits in either ring, so neither can overflow below it.
  if (in_flight_ >= options_.capacity) return Submit::Full;
  bool pushed = submissions_.push({tx, std::chrono::steady_clock::now()});
  assert(pushed);
  (void)pushed;
  ++in_flight_;
  wake_.fetch_add(1, std::memory_order_release);
  wake_.notify_one();  // no system call unless the worker waits
  return Submit::Accepted;
}

std::size_t LedgerCommitter::poll(std::vector<Outcome>& out, std::size_t max) {
  std::size_t n = 0;
  while (n < max) {
    auto outcome = outcomes_.pop();
    if (!outcome) break;
    out.push_back(std::move(*outcome));
    --in_flight_;
    ++n;
  }
  return n;
}

void LedgerCommitter::stop() {
  std::call_once(stop_once_, [this] {
    {
      std::lock_guard lock(sleep_mutex_);
      stopping_.store(true);
    }
    sleep_cv_.notify_all();
    wake_.fetch_add(1, std::memory_order_release);
    wake_.notify_all();
    if (worker_.joinable()) worker_.join();
  });
}

CommitterStats LedgerCommitter::stats() const {
  CommitterStats s;
  s.committed = counters_.committed.load();
  s.already_committed = counters_.already_committed.load();
  s.conflicts = counters_.conflicts.load();
  s.failed = counters_.failed.load();
  s.batches = counters_.batches.load();
  s.attempts_unavailable = counters_.attempts_unavailable.load();
  return s;
}

void LedgerCommitter::emit(const Transaction& tx, TxStatus status, std::string reason) {
  switch (status) {
    case TxStatus::Committed:
      counters_.committed.fetch_add(1, std::memory_order_relaxed);
      break;
    case TxStatus::AlreadyCommitted:
      counters_.already_committed.fetch_add(1, std::memory_order_relaxed);
      break;
    case TxStatus::Conflict:
      counters_.conflicts.fetch_add(1, std::memory_order_relaxed);
      break;
    case TxStatus::Failed:
      counters_.failed.fetch_add(1, std::memory_order_relaxed);
      break;
  }
  bool pushed = outcomes_.push({tx, status, std::move(reason)});
  assert(pushed);  // at most `capacity` are in flight
  (void)pushed;
}

bool LedgerCommitter::sleepFor(std::chrono::milliseconds backoff) {
  std::unique_lock lock(sleep_mutex_);
  return !sleep_cv_.wait_for(lock, backoff, [this] { return stopping_.load(); });
}

void LedgerCommitter::run() {
  std::deque<Pending> pending;
  std::vector<Transaction> batch;
  batch.reserve(options_.max_batch);
  auto backoff = options_.retry_initial;
  auto failFront = [&](std::size_t n, const std::string& reason) {
    for (std::size_t i = 0; i < n; ++i) {
      emit(pending.front().tx, TxStatus::Failed, reason);
      pending.pop_front();
    }
  };
  for (;;) {
    std::uint64_t seen = wake_.load(std::memory_order_acquire);
    while (auto p = submissions_.pop()) pending.push_back(*p);
    if (pending.empty()) {
      if (stopping_.load()) return;
      wake_.wait(seen, std::memory_order_acquire);
      continue;
    }
    std::size_t n = std::min(options_.max_batch, pending.size());
    batch.clear();
    for (std::size_t i = 0; i < n; ++i) batch.push_back(pending[i].tx);
    try {
      std::vector<TxResult> results = store_->commit(batch);
      assert(results.size() == n);
      counters_.batches.fetch_add(1, std::memory_order_relaxed);
      for (std::size_t i = 0; i < n; ++i) {
        emit(pending.front().tx, results[i].status, std::move(results[i].reason));
        pending.pop_front();
      }
      backoff = options_.retry_initial;
    } catch (const StoreError& e) {
      if (e.failure() == StoreFailure::Full) {
        failFront(n, std::string("database full: ") + e.what());
        continue;
      }
      if (e.failure() == StoreFailure::Error) {
        failFront(n, std::string("database error: ") + e.what());
        continue;
      }
      counters_.attempts_unavailable.fetch_add(1, std::memory_order_relaxed);
      const std::string reason = std::string("database unavailable: ") + e.what();
      if (stopping_.load()) {
        failFront(pending.size(), reason + " (committer stopped)");
        continue;  // takes in what was submitted meanwhile, then ends
      }
      // Accepted in order with one deadline, so the expired ones are at the front.
      const auto now = std::chrono::steady_clock::now();
      std::size_t expired = 0;
      while (expired < pending.size() && now - pending[expired].accepted >= options_.deadline) {
        ++expired;
      }
      failFront(expired, reason);
      sleepFor(backoff);
      backoff = std::min(backoff * 2, options_.retry_max);
    }
  }
}

}  // namespace zonesim::ledger
