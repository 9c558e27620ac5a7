// The conformance suite on a real PostgreSQL server (pg_server.h), and what a server adds:
// connection strings, a server that dies under a committer and comes back.

#include "ledger/postgres_store.h"

#include <gtest/gtest.h>
#include <libpq-fe.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>

#include "committer_support.h"
#include "ledger/committer.h"
#include "pg_server.h"
#include "store_conformance.h"

namespace zonesim::ledger::test {
namespace {

// The server, or a test failure that says why it could not start (never a skip: CI has it).
PgServer* server() {
  try {
    return &sharedServer();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "cannot start a PostgreSQL server: " << e.what();
    return nullptr;
  }
}

// A fresh database per test on the binary's one server.
class PgHarness : public StoreHarness {
 public:
  PgHarness() {
    PgServer* s = server();
    if (!s) throw std::runtime_error("no PostgreSQL server");
    static std::atomic<int> counter{0};
    dbname_ = "ledger_" + std::to_string(++counter);
    s->createDatabase(dbname_);
    conninfo_ = s->conninfo(dbname_);
  }
  std::unique_ptr<LedgerStore> open() override {
    return std::make_unique<PostgresStore>(PostgresOptions{.conninfo = conninfo_});
  }
  const std::string& conninfo() const { return conninfo_; }

 private:
  std::string dbname_, conninfo_;
};

INSTANTIATE_TEST_SUITE_P(Postgres, StoreConformance,
                         ::testing::Values(BackendParam{
                             "postgres", [] { return std::make_unique<PgHarness>(); }}),
                         backendName);

TEST(PostgresStore, BadConnectionStringsSayWhatIsWrong) {
  try {
    PostgresStore store({.conninfo = "host=/tmp dbname"});
    FAIL() << "no error for a malformed connection string";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bad connection string"), std::string::npos) << e.what();
  }
  try {
    PostgresStore store({.conninfo = "host=/nonexistent/socket/dir port=1 dbname=x"});
    FAIL() << "no error for a server that is not there";
  } catch (const StoreError& e) {
    EXPECT_EQ(e.failure(), StoreFailure::Unavailable);
    std::string what = e.what();
    EXPECT_NE(what.find("cannot connect"), std::string::npos) << what;
    EXPECT_NE(what.find("host=/nonexistent/socket/dir"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "more than one line: " << what;
  }
  EXPECT_THROW(openStore({.backend = "postgres", .target = ""}), std::invalid_argument);
}

TEST(PostgresStore, NeverShowsThePassword) {
  try {
    PostgresStore store({.conninfo = "host=/nonexistent port=1 password=hunter2 dbname=x"});
    FAIL() << "connected to nothing";
  } catch (const StoreError& e) {
    EXPECT_EQ(std::string(e.what()).find("hunter2"), std::string::npos) << e.what();
  }
}

class PostgresRestart : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = server();
    ASSERT_NE(server_, nullptr);
    ASSERT_NO_THROW(harness_ = std::make_unique<PgHarness>());
  }
  void TearDown() override {
    // Whatever failed, the next test finds the server up.
    if (server_ && !server_->running()) server_->start();
  }
  PgServer* server_ = nullptr;
  std::unique_ptr<PgHarness> harness_;
};

// A store whose server restarted fails its next call as Unavailable at most once, then works
// on a new connection.
TEST_F(PostgresRestart, TheStoreReconnectsAfterTheServerRestarts) {
  auto store = harness_->open();
  Transaction tx = makeTx(1, 1);
  ASSERT_EQ(store->commit({&tx, 1})[0].status, TxStatus::Committed);
  server_->kill();
  try {
    store->counts();
    FAIL() << "counted on a dead server";
  } catch (const StoreError& e) {
    EXPECT_EQ(e.failure(), StoreFailure::Unavailable) << e.what();
  }
  server_->start();
  int unavailable = 0;
  std::uint64_t total = 0;
  for (int attempt = 0; attempt < 2; ++attempt) {
    try {
      total = store->counts().total;
      break;
    } catch (const StoreError& e) {
      ASSERT_EQ(e.failure(), StoreFailure::Unavailable) << e.what();
      ++unavailable;
    }
  }
  EXPECT_LE(unavailable, 1);
  EXPECT_EQ(total, 1u);
}

// The case: the server goes down under a committer; what is submitted meanwhile waits
// (no outcome) and commits after the restart.
TEST_F(PostgresRestart, DatabaseDownTransactionsWaitAndCommitAfterTheRestart) {
  LedgerCommitter committer(harness_->open(), {.deadline = std::chrono::minutes(10),
                                               .retry_max = std::chrono::milliseconds(200)});
  std::vector<Outcome> outcomes;
  for (std::uint64_t s = 1; s <= 100; ++s)
    ASSERT_EQ(committer.submit(makeTx(9, s)), Submit::Accepted);
  ASSERT_TRUE(waitForOutcomes(committer, outcomes, 100));

  server_->kill();
  for (std::uint64_t s = 101; s <= 200; ++s)
    ASSERT_EQ(committer.submit(makeTx(9, s)), Submit::Accepted);
  ASSERT_TRUE(waitUntil([&] { return committer.stats().attempts_unavailable >= 3; }));
  EXPECT_EQ(committer.poll(outcomes), 0u) << "an outcome while the server was down";
  server_->start();
  ASSERT_TRUE(waitForOutcomes(committer, outcomes, 200));
  for (const auto& o : outcomes) EXPECT_EQ(o.status, TxStatus::Committed) << o.reason;
  committer.stop();
  auto store = harness_->open();
  EXPECT_EQ(store->counts().total, 200u);
  EXPECT_EQ(store->highestSequence(9), 200u);
}

// Killed while batches stream in: a batch in flight at the kill may have committed without
// its answer; its retry comes back AlreadyCommitted. Nothing fails, nothing is applied twice.
TEST_F(PostgresRestart, KilledMidStreamEveryTransactionCommitsOnce) {
  LedgerCommitter committer(harness_->open(), {.capacity = 256,
                                               .max_batch = 16,
                                               .deadline = std::chrono::minutes(10),
                                               .retry_max = std::chrono::milliseconds(200)});
  const std::uint64_t n = 3000;
  std::vector<Outcome> outcomes;
  bool killed = false, restarted = false;
  for (std::uint64_t i = 0; i < n;) {
    Submit s = committer.submit(makeTx(1 + i % 20, 1 + i / 20, Kind::Purchase));
    if (s == Submit::Accepted) {
      ++i;
    } else {
      ASSERT_EQ(s, Submit::Full);
      committer.poll(outcomes);
    }
    if (!killed && outcomes.size() >= 500) {
      server_->kill();
      killed = true;
    }
    if (killed && !restarted && committer.stats().attempts_unavailable >= 2) {
      server_->start();
      restarted = true;
    }
    if (killed && !restarted && committer.inFlight() >= 256) {
      ASSERT_TRUE(waitUntil([&] { return committer.stats().attempts_unavailable >= 2; }));
    }
  }
  ASSERT_TRUE(killed);
  if (!restarted) server_->start();
  ASSERT_TRUE(waitForOutcomes(committer, outcomes, n));
  std::map<TxStatus, int> by_status;
  for (const auto& o : outcomes) {
    ++by_status[o.status];
    EXPECT_TRUE(o.status == TxStatus::Committed || o.status == TxStatus::AlreadyCommitted)
        << statusName(o.status) << ": " << o.reason;
  }
  committer.stop();
  EXPECT_EQ(harness_->open()->counts().total, n);
  EXPECT_GE(committer.stats().attempts_unavailable, 1u);
  std::printf("outcomes: %d committed, %d already committed (answers lost at the kill)\n",
              by_status[TxStatus::Committed], by_status[TxStatus::AlreadyCommitted]);
}

// Runs one SQL command; throws std::runtime_error with the server's message.
void execSql(const std::string& conninfo, const std::string& sql) {
  std::unique_ptr<PGconn, void (*)(PGconn*)> conn(PQconnectdb(conninfo.c_str()), PQfinish);
  std::unique_ptr<PGresult, void (*)(PGresult*)> res(PQexec(conn.get(), sql.c_str()), PQclear);
  if (PQresultStatus(res.get()) != PGRES_COMMAND_OK) {
    throw std::runtime_error(sql + ": " + PQerrorMessage(conn.get()));
  }
}

// A small tmpfs for a tablespace: a disk that really fills. Unmounted (lazily, so a server
// still holding a file cannot keep it) and removed at the end.
class SmallDisk {
 public:
  SmallDisk(const std::string& path, const char* size) : path_(path) {
    std::filesystem::create_directories(path_);
    std::string options = std::string("size=") + size + ",mode=0700";
    if (geteuid() == 0) {
      struct stat st {};
      stat(std::filesystem::path(path_).parent_path().c_str(), &st);  // the server's folder
      options += ",uid=" + std::to_string(st.st_uid) + ",gid=" + std::to_string(st.st_gid);
    }
    if (mount("tmpfs", path_.c_str(), "tmpfs", 0, options.c_str()) != 0) {
      throw std::runtime_error("cannot mount a " + std::string(size) + " tmpfs on " + path_ +
                               " (this test needs root): " + std::strerror(errno));
    }
  }
  ~SmallDisk() {
    umount2(path_.c_str(), MNT_DETACH);
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;

 private:
  std::string path_;
};

// The ledger's table and index on a 1 MiB disk: the batch that does not fit fails as Full
// (SQLSTATE 53100) and leaves nothing behind; through a committer the outcome is
// "database full: ...".
TEST_F(PostgresRestart, ADiskThatFillsFailsTheBatchAsFull) {
  const std::string dir = server_->folder() + "/small_disk";
  std::unique_ptr<SmallDisk> disk;
  ASSERT_NO_THROW(disk = std::make_unique<SmallDisk>(dir, "1m"));
  struct DropTablespace {
    std::string conninfo;
    ~DropTablespace() {
      try {
        execSql(conninfo, "DROP TABLESPACE IF EXISTS ledger_small");
      } catch (...) {
      }
    }
  } drop{server_->conninfo()};
  ASSERT_NO_THROW(
      execSql(server_->conninfo(), "CREATE TABLESPACE ledger_small LOCATION '" + dir + "'"));
  auto store = harness_->open();  // creates the table, on the default tablespace
  ASSERT_NO_THROW(execSql(harness_->conninfo(),
                          "ALTER TABLE ledger_tx SET TABLESPACE ledger_small;"
                          " ALTER INDEX ledger_tx_pkey SET TABLESPACE ledger_small;"
                          " ALTER INDEX ledger_tx_scores SET TABLESPACE ledger_small"));
  std::uint64_t committed = 0;
  std::string error;
  for (std::uint64_t round = 1; round < 2000 && error.empty(); ++round) {
    std::vector<Transaction> batch;
    for (std::uint64_t s = 1; s <= 100; ++s) batch.push_back(makeTx(round, s));
    try {
      store->commit(batch);
      committed += batch.size();
    } catch (const StoreError& e) {
      EXPECT_EQ(e.failure(), StoreFailure::Full) << e.what();
      error = e.what();
    }
  }
  ASSERT_FALSE(error.empty()) << "1 MiB never filled";
  EXPECT_GT(committed, 0u);
  EXPECT_EQ(store->counts().total, committed);

  LedgerCommitter committer(harness_->open());
  for (std::uint64_t s = 1; s <= 300; ++s) committer.submit(makeTx(1'000'000, s));
  std::vector<Outcome> outcomes;
  ASSERT_TRUE(waitForOutcomes(committer, outcomes, 300));
  for (const auto& o : outcomes) {
    EXPECT_EQ(o.status, TxStatus::Failed);
    EXPECT_EQ(o.reason.rfind("database full: ", 0), 0u) << o.reason;
  }
  committer.stop();
  EXPECT_EQ(store->counts().total, committed);
  store.reset();
  execSql(harness_->conninfo(), "DROP TABLE ledger_tx");
}

}  // namespace
}  // namespace zonesim::ledger::test
