#pragma once
// The zone tick's way to the ledger: submit() and poll() never block and never wait for the
// database; a worker thread commits in batches and hands back one Outcome per accepted
// transaction, in the order it learned them.
//
// Guarantees (tests/ledger/committer_test.cpp):
// - Every transaction submit() accepted gets exactly one Outcome; none is dropped or repeated,
//   whatever the database does, and stop() gives the rest theirs (Failed, with the reason).
// - Committed and AlreadyCommitted both mean "durable in the database": only then may the
//   client be told it succeeded. AlreadyCommitted is a retry of a key stored before (a resent
//   transaction, or a commit whose answer a lost connection swallowed).
// - Unavailable database (down, locked, connection lost): transactions wait, the worker retries
//   with exponential backoff, and one that waited longer than `deadline` since it was accepted
//   is Failed, "database unavailable: ...". A full database or any other error fails the batch
//   at once with the database's reason; nothing of a failed batch is applied.
//
// Threads: submit(), poll(), inFlight() and stop() belong to one thread (the tick's): a
// submit() racing a stop() on another thread could hand the worker a transaction after its
// last look. stats() may be called from any.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "ledger/spsc_ring.h"
#include "ledger/store.h"

namespace zonesim::ledger {

struct CommitterOptions {
  /// Transactions accepted and not yet polled as outcomes; beyond it submit() says Full.
  std::size_t capacity = 4096;
  /// The most transactions in one database transaction.
  std::size_t max_batch = 256;
  /// How long a transaction may wait for an unavailable database before it fails.
  std::chrono::milliseconds deadline{10'000};
  /// Backoff between attempts while the database is unavailable: doubles up to retry_max.
  std::chrono::milliseconds retry_initial{10};
  std::chrono::milliseconds retry_max{1'000};
};

/// What submit() did: only Accepted ones get an Outcome.
enum class Submit : std::uint8_t { Accepted, Full, Invalid, Stopped };

/// "accepted", "full", "invalid", "stopped".
std::string_view submitName(Submit submit);

/// The fate of one accepted transaction.
struct Outcome {
  Transaction tx;
  TxStatus status = TxStatus::Failed;
  std::string reason;
};

/// Counters of the worker, for metrics.
struct CommitterStats {
  std::uint64_t committed = 0, already_committed = 0, conflicts = 0, failed = 0;
  std::uint64_t batches = 0;               ///< database transactions that committed
  std::uint64_t attempts_unavailable = 0;  ///< attempts that found the database unavailable
};

class LedgerCommitter {
 public:
  /// Starts the worker; it alone uses `store` from now on.
  explicit LedgerCommitter(std::unique_ptr<LedgerStore> store, CommitterOptions options = {});
  /// stop(), then joins.
  ~LedgerCommitter();
  LedgerCommitter(const LedgerCommitter&) = delete;
  LedgerCommitter& operator=(const LedgerCommitter&) = delete;

  /// Hands `tx` to the worker without waiting: Full when `capacity` are in flight (poll, then
  /// try again next tick), Invalid for a transaction no store would take (invalidReason).
  Submit submit(const Transaction& tx);
  /// Moves up to `max` outcomes into `out` (appended) without waiting; returns how many.
  std::size_t poll(std::vector<Outcome>& out, std::size_t max = SIZE_MAX);
  /// Accepted and not yet polled.
  std::size_t inFlight() const { return in_flight_; }
  /// Commits what it can of what was accepted (one attempt, no waiting on an unavailable
  /// database), fails the rest, and ends the worker. Outcomes stay for poll(). Idempotent.
  void stop();
  CommitterStats stats() const;

 private:
  struct Pending {
    Transaction tx;
    std::chrono::steady_clock::time_point accepted;
  };
  void run();
  void emit(const Transaction& tx, TxStatus status, std::string reason);
  bool sleepFor(std::chrono::milliseconds backoff);

  std::unique_ptr<LedgerStore> store_;
  CommitterOptions options_;
  SpscRing<Pending> submissions_;
  SpscRing<Outcome> outcomes_;
  std::size_t in_flight_ = 0;  // the tick thread's alone: +1 on accept, -1 on poll
  std::atomic<std::uint64_t> wake_{0};
  std::atomic<bool> stopping_{false};
  std::mutex sleep_mutex_;
  std::condition_variable sleep_cv_;
  std::once_flag stop_once_;
  struct Counters {
    std::atomic<std::uint64_t> committed{0}, already_committed{0}, conflicts{0}, failed{0},
        batches{0}, attempts_unavailable{0};
  } counters_;
  std::thread worker_;
};

}  // namespace zonesim::ledger
