#pragma once
// The one storage interface of the ledger, with two back ends: SqliteStore (embedded, the
// default) and PostgresStore (a server). Guarantees every back end keeps (tests/ledger's
// conformance suite runs the same cases on both):
// - commit() applies a batch in one database transaction: either it returns one result per
//   transaction, in order, and everything it reports committed is durable; or it throws
//   StoreError and nothing of the batch was applied.
// - (player, seq) is the idempotency key. A transaction whose key is stored already, with the
//   same request (transaction.h, sameRequest: any tick), is AlreadyCommitted (not applied
//   again); with another request it is a Conflict and the stored one stays. Within one batch the first of a key decides.
// - An invalid transaction (transaction.h, invalidReason) is Failed with the reason; the rest
//   of its batch goes on.

#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "ledger/transaction.h"

namespace zonesim::ledger {

/// The fate of one transaction in a batch that reached the database.
enum class TxStatus : std::uint8_t { Committed, AlreadyCommitted, Conflict, Failed };

/// "committed", "already_committed", "conflict", "failed".
std::string_view statusName(TxStatus status);

/// One transaction's result; `reason` says why for Conflict and Failed.
struct TxResult {
  TxStatus status = TxStatus::Failed;
  std::string reason;
};

/// Why a whole operation failed: Unavailable may pass (server down, locked, connection lost:
/// retry), Full is out of space, Error is anything else (I/O, corruption, a refused schema).
enum class StoreFailure : std::uint8_t { Unavailable, Full, Error };

/// "unavailable", "full", "error".
std::string_view failureName(StoreFailure failure);

/// A database operation that did not happen; what() is one line naming the back end and cause.
class StoreError : public std::runtime_error {
 public:
  StoreError(StoreFailure failure, const std::string& what)
      : std::runtime_error(what), failure_(failure) {}
  StoreFailure failure() const { return failure_; }

 private:
  StoreFailure failure_;
};

/// One leaderboard row: a player's best score and the tick it was first reached at.
struct LeaderboardRow {
  std::uint64_t player = 0;
  std::int64_t score = 0;
  std::uint64_t tick = 0;
  bool operator==(const LeaderboardRow&) const = default;
};

/// How many transactions are stored, in all and by kind (indexed by Kind's value).
struct LedgerCounts {
  std::uint64_t total = 0;
  std::uint64_t by_kind[5] = {};
  std::uint64_t of(Kind kind) const { return by_kind[std::size_t(kind)]; }
};

/// The storage interface; one instance is used by one thread at a time.
class LedgerStore {
 public:
  virtual ~LedgerStore() = default;
  /// "sqlite" or "postgres".
  virtual std::string_view backend() const = 0;
  /// Stores `batch` atomically and idempotently (see the top of this file); throws StoreError.
  virtual std::vector<TxResult> commit(std::span<const Transaction> batch) = 0;
  /// The highest committed sequence of `player`, 0 if none: where a resumed client goes on.
  virtual std::uint64_t highestSequence(std::uint64_t player) = 0;
  /// The top `n` players by best score; ties go to whoever reached it at the earlier tick,
  /// then to the lower player id.
  virtual std::vector<LeaderboardRow> leaderboard(std::size_t n) = 0;
  virtual LedgerCounts counts() = 0;
};

/// Which back end and where: `target` is a file path for "sqlite", a libpq connection string
/// (keyword=value or a postgresql:// URI) for "postgres".
struct StoreConfig {
  std::string backend = "sqlite";
  std::string target;
};

/// "sqlite:PATH" or "postgres:CONNINFO" (the form of zone_node --ledger). Throws
/// std::invalid_argument naming what is wrong (no colon, an unknown back end, no target).
StoreConfig parseStoreSpec(std::string_view spec);

/// Opens the store and creates or checks its schema. Throws std::invalid_argument for an
/// unknown back end or an empty target, StoreError when the database cannot be opened.
std::unique_ptr<LedgerStore> openStore(const StoreConfig& config);

}  // namespace zonesim::ledger
