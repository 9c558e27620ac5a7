#include "ledger/sqlite_store.h"

#include <sqlite3.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <thread>

#include "ledger/batch_plan.h"
#include "ledger/schema.h"

namespace zonesim::ledger {
namespace {

static_assert(int(Kind::Score) == 4, "schema.h's score queries say kind = 4");

StoreFailure failureOf(int code) {
  switch (code & 0xff) {
    case SQLITE_FULL:
      return StoreFailure::Full;
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      return StoreFailure::Unavailable;
    default:
      return StoreFailure::Error;
  }
}

// A prepared statement, reset after each use so it holds no lock between calls.
class Statement {
 public:
  Statement() = default;
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  ~Statement() { sqlite3_finalize(stmt_); }
  sqlite3_stmt*& raw() { return stmt_; }
  sqlite3_stmt* get() const { return stmt_; }

 private:
  sqlite3_stmt* stmt_ = nullptr;
};

struct ResetGuard {
  sqlite3_stmt* stmt;
  ~ResetGuard() {
    sqlite3_reset(stmt);
    sqlite3_clear_bindings(stmt);
  }
};

std::int64_t asSigned(std::uint64_t v) {
  return std::int64_t(v);
}

}  // namespace

// Closed after the statements, which are declared after it in Impl.
struct Connection {
  sqlite3* db = nullptr;
  Connection() = default;
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;
  ~Connection() { sqlite3_close_v2(db); }
};

struct SqliteStore::Impl {
  SqliteOptions options;
  Connection connection;
  sqlite3*& db = connection.db;
  Statement insert, select_one, highest, leaderboard, counts;

  [[noreturn]] void fail(const std::string& what, int code) const {
    throw StoreError(failureOf(code), "sqlite '" + options.path + "': " + what + ": " +
                                          (db ? sqlite3_errmsg(db) : sqlite3_errstr(code)));
  }

  void exec(const std::string& sql, const char* what) {
    int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr);
    if (rc != SQLITE_OK) fail(what, rc);
  }

  void prepare(Statement& stmt, const std::string& sql) {
    int rc =
        sqlite3_prepare_v3(db, sql.c_str(), -1, SQLITE_PREPARE_PERSISTENT, &stmt.raw(), nullptr);
    if (rc != SQLITE_OK) fail("prepare \"" + sql + "\"", rc);
  }

  // Steps a statement that returns at most one row; true if it returned one.
  bool step(sqlite3_stmt* stmt, const char* what) {
    int rc = sqlite3_step(stmt);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    fail(what, rc);
  }

  void rollback() noexcept {
    if (!sqlite3_get_autocommit(db)) sqlite3_exec(db, "ROLLBACK", nullptr, nullptr, nullptr);
  }

  void open() {
    int rc = sqlite3_open_v2(
        options.path.c_str(), &db,
        SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX | SQLITE_OPEN_URI,
        nullptr);
    if (rc != SQLITE_OK) fail("cannot open the ledger file", rc);
    sqlite3_extended_result_codes(db, 1);
    if (sqlite3_db_readonly(db, "main") == 1) {
      throw StoreError(StoreFailure::Error,
                       "sqlite '" + options.path + "': the ledger file is read-only");
    }
    sqlite3_busy_timeout(db, options.busy_timeout_ms);
    // Ranks of one cluster open a shared file at the same instant. Switching a new file to WAL
    // can then answer "database is locked" at once, without waiting in the busy handler
    // (SQLite refuses to wait where waiting could deadlock), so the open itself retries.
    whileBusy([&] { setWalMode(); });
    exec(options.synchronous_full ? "PRAGMA synchronous=FULL" : "PRAGMA synchronous=NORMAL",
         "set synchronous");
    if (options.max_page_count > 0) {
      exec("PRAGMA max_page_count=" + std::to_string(options.max_page_count), "set max_page_count");
    }
    whileBusy([&] { migrate(); });
    prepare(insert, std::string("INSERT INTO ledger_tx (") + schema::kColumns +
                        ") VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)"
                        " ON CONFLICT (player, seq) DO NOTHING");
    prepare(select_one, std::string("SELECT ") + schema::kColumns +
                            " FROM ledger_tx WHERE player = ?1 AND seq = ?2");
    prepare(highest, "SELECT COALESCE(MAX(seq), 0) FROM ledger_tx WHERE player = ?1");
    prepare(leaderboard, std::string(schema::kLeaderboardBody) + "?1");
    prepare(counts, schema::kCounts);
  }

  // journal_mode answers with the mode it got: anything but wal (a file system without shared
  // memory, say) would silently lose the readers-never-block-writers property.
  void setWalMode() {
    Statement mode;
    prepare(mode, "PRAGMA journal_mode=WAL");
    if (!step(mode.get(), "set journal_mode=WAL")) fail("set journal_mode=WAL", SQLITE_ERROR);
    const char* got = reinterpret_cast<const char*>(sqlite3_column_text(mode.get(), 0));
    if (!got || std::strcmp(got, "wal") != 0) {
      throw StoreError(StoreFailure::Error, "sqlite '" + options.path +
                                                "': WAL mode refused (journal_mode is " +
                                                (got ? got : "unknown") + ")");
    }
  }

  // Runs a step of opening again while it fails as Unavailable (locked by another connection),
  // until the busy timeout has passed; then the last failure stands.
  template <typename Step>
  void whileBusy(Step step) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::milliseconds(options.busy_timeout_ms);
    for (;;) {
      try {
        step();
        return;
      } catch (const StoreError& e) {
        if (e.failure() != StoreFailure::Unavailable ||
            std::chrono::steady_clock::now() >= deadline) {
          throw;
        }
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }

  void migrate() {
    exec("BEGIN IMMEDIATE", "begin schema transaction");
    try {
      exec(schema::kCreateMeta, "create ledger_meta");
      exec(schema::kCreateTx, "create ledger_tx");
      exec(schema::kCreateScoreIndex, "create the score index");
      std::optional<std::int64_t> found;
      {
        Statement version;  // finalized before COMMIT, which refuses a statement in progress
        prepare(version, "SELECT value FROM ledger_meta WHERE key = 'schema_version'");
        if (step(version.get(), "read the schema version")) {
          found = sqlite3_column_int64(version.get(), 0);
        }
      }
      if (found && *found != schema::kVersion) {
        throw StoreError(StoreFailure::Error, "sqlite '" + options.path + "': schema version " +
                                                  std::to_string(*found) + ", this build knows " +
                                                  std::to_string(schema::kVersion));
      }
      if (!found) {
        exec("INSERT INTO ledger_meta (key, value) VALUES ('schema_version', " +
                 std::to_string(schema::kVersion) + ")",
             "write the schema version");
      }
      exec("COMMIT", "commit the schema");
    } catch (...) {
      rollback();
      throw;
    }
  }

  Transaction rowOf(sqlite3_stmt* stmt) const {
    Transaction tx;
    tx.player = std::uint64_t(sqlite3_column_int64(stmt, 0));
    tx.seq = std::uint64_t(sqlite3_column_int64(stmt, 1));
    tx.kind = Kind(sqlite3_column_int(stmt, 2));
    tx.item = std::uint64_t(sqlite3_column_int64(stmt, 3));
    tx.amount = sqlite3_column_int64(stmt, 4);
    tx.counterparty = std::uint64_t(sqlite3_column_int64(stmt, 5));
    tx.price = sqlite3_column_int64(stmt, 6);
    tx.score = sqlite3_column_int64(stmt, 7);
    tx.tick = std::uint64_t(sqlite3_column_int64(stmt, 8));
    return tx;
  }

  KeyWrite write(const Transaction& tx) {
    {
      sqlite3_stmt* s = insert.get();
      ResetGuard reset{s};
      sqlite3_bind_int64(s, 1, asSigned(tx.player));
      sqlite3_bind_int64(s, 2, asSigned(tx.seq));
      sqlite3_bind_int(s, 3, int(tx.kind));
      sqlite3_bind_int64(s, 4, asSigned(tx.item));
      sqlite3_bind_int64(s, 5, tx.amount);
      sqlite3_bind_int64(s, 6, asSigned(tx.counterparty));
      sqlite3_bind_int64(s, 7, tx.price);
      sqlite3_bind_int64(s, 8, tx.score);
      sqlite3_bind_int64(s, 9, asSigned(tx.tick));
      step(s, "insert");
      if (sqlite3_changes(db) == 1) return {true, tx};
    }
    sqlite3_stmt* s = select_one.get();
    ResetGuard reset{s};
    sqlite3_bind_int64(s, 1, asSigned(tx.player));
    sqlite3_bind_int64(s, 2, asSigned(tx.seq));
    if (!step(s, "read the stored transaction")) {
      fail("a conflicting insert found no row for " + describe(tx), SQLITE_ERROR);
    }
    return {false, rowOf(s)};
  }
};

SqliteStore::SqliteStore(const SqliteOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->open();
}

SqliteStore::~SqliteStore() = default;

std::vector<TxResult> SqliteStore::commit(std::span<const Transaction> batch) {
  BatchPlan plan = planBatch(batch);
  std::vector<KeyWrite> writes;
  writes.reserve(plan.to_store.size());
  if (!plan.to_store.empty()) {
    // IMMEDIATE takes the write lock now, so a busy database fails here, before any row.
    impl_->exec("BEGIN IMMEDIATE", "begin");
    try {
      for (std::size_t i : plan.to_store) writes.push_back(impl_->write(batch[i]));
      impl_->exec("COMMIT", "commit");
    } catch (...) {
      impl_->rollback();
      throw;
    }
  }
  return batchResults(batch, plan, writes);
}

std::uint64_t SqliteStore::highestSequence(std::uint64_t player) {
  sqlite3_stmt* s = impl_->highest.get();
  ResetGuard reset{s};
  sqlite3_bind_int64(s, 1, asSigned(player));
  if (!impl_->step(s, "read the highest sequence")) return 0;
  return std::uint64_t(sqlite3_column_int64(s, 0));
}

std::vector<LeaderboardRow> SqliteStore::leaderboard(std::size_t n) {
  std::vector<LeaderboardRow> rows;
  sqlite3_stmt* s = impl_->leaderboard.get();
  ResetGuard reset{s};
  sqlite3_bind_int64(s, 1, std::int64_t(std::min<std::size_t>(n, INT64_MAX)));
  while (impl_->step(s, "read the leaderboard")) {
    rows.push_back({std::uint64_t(sqlite3_column_int64(s, 0)), sqlite3_column_int64(s, 1),
                    std::uint64_t(sqlite3_column_int64(s, 2))});
  }
  return rows;
}

LedgerCounts SqliteStore::counts() {
  LedgerCounts counts;
  sqlite3_stmt* s = impl_->counts.get();
  ResetGuard reset{s};
  while (impl_->step(s, "count transactions")) {
    auto kind = sqlite3_column_int(s, 0);
    auto n = std::uint64_t(sqlite3_column_int64(s, 1));
    counts.total += n;
    if (kind > 0 && kind < 5) counts.by_kind[kind] = n;
  }
  return counts;
}

}  // namespace zonesim::ledger
