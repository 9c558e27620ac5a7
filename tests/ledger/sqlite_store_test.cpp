// The conformance suite on SQLite, and what only SQLite has: paths that cannot be opened, a
// full database (PRAGMA max_page_count), another connection holding the write lock, and many
// processes opening one new file at once (a cluster's ranks sharing a ledger).

#include "ledger/sqlite_store.h"

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "store_conformance.h"
#include "temp_dir.h"

namespace zonesim::ledger::test {
namespace {

class SqliteHarness : public StoreHarness {
 public:
  std::unique_ptr<LedgerStore> open() override {
    return std::make_unique<SqliteStore>(SqliteOptions{.path = dir_.file("ledger.db")});
  }

 private:
  TempDir dir_;
};

INSTANTIATE_TEST_SUITE_P(Sqlite, StoreConformance,
                         ::testing::Values(BackendParam{
                             "sqlite", [] { return std::make_unique<SqliteHarness>(); }}),
                         backendName);

// The message of the StoreError that `open` throws; empty if it throws none.
template <typename F>
std::string openError(F open, StoreFailure* failure = nullptr) {
  try {
    open();
  } catch (const StoreError& e) {
    if (failure) *failure = e.failure();
    return e.what();
  }
  return {};
}

TEST(SqliteStore, APathThatCannotBeOpenedNamesPathAndCause) {
  TempDir dir;
  const std::string missing = dir.file("no/such/folder/ledger.db");
  std::string error = openError([&] { SqliteStore store({.path = missing}); });
  EXPECT_NE(error.find(missing), std::string::npos) << error;
  EXPECT_NE(error.find("cannot open"), std::string::npos) << error;

  // A folder where the file should be.
  error = openError([&] { SqliteStore store({.path = dir.path().string()}); });
  EXPECT_NE(error.find(dir.path().string()), std::string::npos) << error;
  EXPECT_FALSE(error.empty());
}

TEST(SqliteStore, AFileThatIsNotALedgerIsRefused) {
  TempDir dir;
  const std::string path = dir.file("notes.txt");
  std::ofstream(path) << "these are not the pages of a database, but long enough to look "
                         "like a header to anyone who only counts bytes: 0123456789abcdef\n";
  StoreFailure failure{};
  std::string error = openError([&] { SqliteStore store({.path = path}); }, &failure);
  EXPECT_EQ(failure, StoreFailure::Error);
  EXPECT_NE(error.find("not a database"), std::string::npos) << error;
}

TEST(SqliteStore, AReadOnlyFileIsRefusedAtOpen) {
  TempDir dir;
  const std::string path = dir.file("ledger.db");
  { SqliteStore store({.path = path}); }
  // Root ignores file modes; a read-only URI opens it the way a write-protected file opens.
  std::string error = openError([&] { SqliteStore store({.path = "file:" + path + "?mode=ro"}); });
  EXPECT_NE(error.find("read-only"), std::string::npos) << error;
}

TEST(SqliteStore, OpenStoreRejectsUnknownBackEndsAndEmptyTargets) {
  try {
    openStore({.backend = "mysql", .target = "x"});
    FAIL() << "no error for an unknown back end";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown back end 'mysql'"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(openStore({.backend = "sqlite", .target = ""}), std::invalid_argument);
  TempDir dir;
  auto store = openStore({.backend = "sqlite", .target = dir.file("l.db")});
  EXPECT_EQ(store->backend(), "sqlite");
}

// zone_node --ledger: BACKEND:TARGET, the target kept whole (a URI has colons of its own), and
// each malformed form refused with what is wrong.
TEST(SqliteStore, AStoreSpecNamesBackEndAndTargetOrSaysWhatIsWrong) {
  StoreConfig c = parseStoreSpec("sqlite:/run/a:b.db");
  EXPECT_EQ(c.backend, "sqlite");
  EXPECT_EQ(c.target, "/run/a:b.db");
  c = parseStoreSpec("postgres:postgresql://zs@localhost:5433/ledger");
  EXPECT_EQ(c.backend, "postgres");
  EXPECT_EQ(c.target, "postgresql://zs@localhost:5433/ledger");
  auto why = [](std::string_view spec) {
    try {
      parseStoreSpec(spec);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(why("ledger.db").find("expected sqlite:PATH or postgres:CONNINFO"), std::string::npos);
  EXPECT_NE(why("mysql:x").find("unknown back end 'mysql'"), std::string::npos);
  EXPECT_NE(why("sqlite:").find("no file path"), std::string::npos);
  EXPECT_NE(why("postgres:").find("no connection string"), std::string::npos);
}

// A batch that does not fit fails as Full and leaves nothing of itself behind; smaller
// batches that fit still commit afterwards.
TEST(SqliteStore, AFullDatabaseFailsTheWholeBatch) {
  TempDir dir;
  SqliteStore store({.path = dir.file("ledger.db"), .max_page_count = 40});
  std::uint64_t committed = 0;
  std::string error;
  StoreFailure failure{};
  for (std::uint64_t round = 1; round < 1000 && error.empty(); ++round) {
    std::vector<Transaction> batch;
    for (std::uint64_t s = 1; s <= 200; ++s) batch.push_back(makeTx(round, s));
    try {
      store.commit(batch);
      committed += batch.size();
    } catch (const StoreError& e) {
      error = e.what();
      failure = e.failure();
    }
  }
  ASSERT_FALSE(error.empty()) << "40 pages never filled";
  EXPECT_EQ(failure, StoreFailure::Full);
  EXPECT_NE(error.find("full"), std::string::npos) << error;
  EXPECT_GT(committed, 0u);
  EXPECT_EQ(store.counts().total, committed);  // nothing of the failed batch
}

TEST(SqliteStore, AWriteLockHeldElsewhereIsUnavailable) {
  TempDir dir;
  const std::string path = dir.file("ledger.db");
  SqliteStore store({.path = path, .busy_timeout_ms = 20});
  sqlite3* other = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &other), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(other, "BEGIN EXCLUSIVE", nullptr, nullptr, nullptr), SQLITE_OK);
  Transaction tx = makeTx(1, 1);
  StoreFailure failure{};
  std::string error = openError([&] { store.commit({&tx, 1}); }, &failure);
  EXPECT_EQ(failure, StoreFailure::Unavailable) << error;
  EXPECT_NE(error.find("locked"), std::string::npos) << error;
  ASSERT_EQ(sqlite3_exec(other, "COMMIT", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(other);
  EXPECT_EQ(store.commit({&tx, 1})[0].status, TxStatus::Committed);
}

// Ranks of a cluster open one shared ledger file at the same instant. Switching a new file to
// WAL then sometimes answered "database is locked" at once (about 1 open in 50 with 4
// processes), and the rank died at startup; the open now retries within its busy timeout.
TEST(SqliteStore, ProcessesOpeningOneNewFileAtOnceAllOpenIt) {
  constexpr int kRounds = 40, kProcesses = 6;
  TempDir dir;
  int failed = 0;
  for (int round = 0; round < kRounds; ++round) {
    const std::string path = dir.file("shared-" + std::to_string(round) + ".db");
    for (int i = 0; i < kProcesses; ++i) {
      pid_t pid = fork();
      ASSERT_GE(pid, 0) << "fork failed";
      if (pid == 0) {
        try {
          SqliteStore store({.path = path});
          _exit(0);
        } catch (const std::exception& e) {
          std::fprintf(stderr, "round %d, process %d: %s\n", round, i, e.what());
          _exit(1);
        }
      }
    }
    for (int i = 0; i < kProcesses; ++i) {
      int status = 0;
      wait(&status);
      failed += !(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    }
  }
  EXPECT_EQ(failed, 0) << "of " << kRounds * kProcesses << " opens";
}

// The retry ends with the busy timeout: a lock held longer still fails the open as Unavailable.
TEST(SqliteStore, AnOpenBehindALongHeldLockFailsAsUnavailable) {
  TempDir dir;
  const std::string path = dir.file("ledger.db");
  { SqliteStore create({.path = path}); }
  sqlite3* other = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &other), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(other, "BEGIN EXCLUSIVE", nullptr, nullptr, nullptr), SQLITE_OK);
  StoreFailure failure{};
  std::string error =
      openError([&] { SqliteStore late({.path = path, .busy_timeout_ms = 50}); }, &failure);
  EXPECT_EQ(failure, StoreFailure::Unavailable) << error;
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_NE(error.find("locked"), std::string::npos) << error;
  ASSERT_EQ(sqlite3_exec(other, "COMMIT", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(other);
}

}  // namespace
}  // namespace zonesim::ledger::test
