#pragma once
// The embedded back end: one SQLite file in WAL mode, a batch in one BEGIN IMMEDIATE
// transaction, prepared statements. sqlite3.h stays in the .cpp.

#include <memory>
#include <string>

#include "ledger/store.h"

namespace zonesim::ledger {

struct SqliteOptions {
  /// A file path, or a file: URI ("file:/srv/ledger.db?mode=ro" opens it read-only and is
  /// refused, since the ledger writes).
  std::string path;
  /// synchronous=FULL (the default) fsyncs the WAL at every commit, so a commit the client was
  /// told of survives a power cut; NORMAL syncs only at checkpoints and may lose the last
  /// commits (never corrupt the file): only for measurements and throw-away runs.
  bool synchronous_full = true;
  /// How long a write waits for another connection's lock before it fails as Unavailable.
  int busy_timeout_ms = 1000;
  /// A limit on the file's size in pages (PRAGMA max_page_count, 4 KiB pages), 0 = none:
  /// a quota, and how the tests fill the "disk".
  long max_page_count = 0;
};

class SqliteStore final : public LedgerStore {
 public:
  /// Opens or creates the file and its schema; throws StoreError naming the path and the cause.
  explicit SqliteStore(const SqliteOptions& options);
  ~SqliteStore() override;
  SqliteStore(const SqliteStore&) = delete;
  SqliteStore& operator=(const SqliteStore&) = delete;

  std::string_view backend() const override { return "sqlite"; }
  std::vector<TxResult> commit(std::span<const Transaction> batch) override;
  std::uint64_t highestSequence(std::uint64_t player) override;
  std::vector<LeaderboardRow> leaderboard(std::size_t n) override;
  LedgerCounts counts() override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace zonesim::ledger
