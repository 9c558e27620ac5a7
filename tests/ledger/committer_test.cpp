// The committer on a real SQLite file: every accepted transaction gets exactly one outcome;
// submit() says Full instead of waiting; a locked ("down") database makes transactions wait,
// then commit, or fail at their deadline with the reason; a full one fails them at once.

#include "ledger/committer.h"

#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "committer_support.h"
#include "ledger/sqlite_store.h"
#include "sqlite_write_lock.h"
#include "store_conformance.h"
#include "temp_dir.h"

namespace zonesim::ledger::test {
namespace {

using Key = std::pair<std::uint64_t, std::uint64_t>;

class CommitterTest : public ::testing::Test {
 protected:
  std::unique_ptr<LedgerStore> store(long max_pages = 0) {
    return std::make_unique<SqliteStore>(
        SqliteOptions{.path = path_, .busy_timeout_ms = 20, .max_page_count = max_pages});
  }
  TempDir dir_;
  std::string path_ = dir_.file("ledger.db");
};

// 3,000 submissions through a 64-slot queue, among them resends of the same transaction and
// changed copies of committed keys: one outcome each, and the database holds each key once.
TEST_F(CommitterTest, EveryAcceptedTransactionGetsExactlyOneOutcome) {
  LedgerCommitter committer(store(), {.capacity = 64, .max_batch = 16});
  std::vector<Transaction> plan;
  for (std::uint64_t i = 0; i < 3000; ++i) {
    std::uint64_t player = 1 + i % 10, seq = 1 + i / 10;
    if (i % 7 == 3) seq = 1;  // a resend of the player's first
    Transaction tx = makeTx(player, seq);
    if (i % 11 == 5 && seq == 1) tx.amount += 100;  // a changed copy: a conflict
    plan.push_back(tx);
  }
  std::vector<Outcome> outcomes;
  std::size_t accepted = 0, full = 0;
  for (std::size_t i = 0; i < plan.size();) {
    Submit s = committer.submit(plan[i]);
    ASSERT_NE(s, Submit::Invalid);
    if (s == Submit::Accepted) {
      ++accepted;
      ++i;
    } else {
      ++full;
      committer.poll(outcomes);  // as the tick would: take outcomes, retry next tick
    }
  }
  ASSERT_TRUE(waitForOutcomes(committer, outcomes, accepted));
  committer.stop();
  EXPECT_EQ(committer.poll(outcomes), 0u) << "more outcomes than submissions";
  EXPECT_EQ(committer.inFlight(), 0u);
  ASSERT_EQ(outcomes.size(), plan.size());

  std::map<Key, int> committed;
  std::map<TxStatus, int> by_status;
  for (const auto& o : outcomes) {
    ++by_status[o.status];
    if (o.status == TxStatus::Committed) ++committed[{o.tx.player, o.tx.seq}];
    EXPECT_NE(o.status, TxStatus::Failed) << o.reason;
  }
  std::map<Key, int> unique;
  for (const auto& tx : plan) unique[{tx.player, tx.seq}] = 1;
  EXPECT_EQ(committed.size(), unique.size());
  for (const auto& [key, n] : committed) EXPECT_EQ(n, 1) << key.first << "/" << key.second;
  EXPECT_GT(by_status[TxStatus::AlreadyCommitted], 0);
  EXPECT_GT(by_status[TxStatus::Conflict], 0);
  EXPECT_GT(full, 0u) << "the queue never filled: the test did not test Full";
  auto stats = committer.stats();
  EXPECT_EQ(stats.committed + stats.already_committed + stats.conflicts + stats.failed,
            plan.size());
  EXPECT_EQ(SqliteStore({.path = path_}).counts().total, unique.size());
}

TEST_F(CommitterTest, SubmitSaysFullInsteadOfWaitingForTheDatabase) {
  LedgerCommitter committer(store(), {.capacity = 8, .deadline = std::chrono::minutes(10)});
  SqliteWriteLock lock(path_);
  for (std::uint64_t s = 1; s <= 8; ++s) {
    ASSERT_EQ(committer.submit(makeTx(1, s)), Submit::Accepted);
  }
  EXPECT_EQ(committer.submit(makeTx(1, 9)), Submit::Full);
  EXPECT_EQ(committer.inFlight(), 8u);
  Transaction bad = makeTx(1, 0);
  EXPECT_EQ(committer.submit(bad), Submit::Invalid);
  lock.release();
  std::vector<Outcome> outcomes;
  ASSERT_TRUE(waitForOutcomes(committer, outcomes, 8));
  EXPECT_EQ(committer.submit(makeTx(1, 9)), Submit::Accepted);
  ASSERT_TRUE(waitForOutcomes(committer, outcomes, 9));
  for (const auto& o : outcomes) EXPECT_EQ(o.status, TxStatus::Committed) << o.reason;
}

// Held behind another connection's lock, transactions wait (no outcome, however many
// attempts), and all commit once the lock goes.
TEST_F(CommitterTest, WhileTheDatabaseIsLockedTransactionsWaitThenCommit) {
  LedgerCommitter committer(store(), {.deadline = std::chrono::minutes(10)});
  std::vector<Outcome> outcomes;
  {
    SqliteWriteLock lock(path_);
    for (std::uint64_t s = 1; s <= 100; ++s) {
      ASSERT_EQ(committer.submit(makeTx(2, s)), Submit::Accepted);
    }
    ASSERT_TRUE(waitUntil([&] { return committer.stats().attempts_unavailable >= 3; }));
    EXPECT_EQ(committer.poll(outcomes), 0u);
  }
  ASSERT_TRUE(waitForOutcomes(committer, outcomes, 100));
  for (const auto& o : outcomes) EXPECT_EQ(o.status, TxStatus::Committed) << o.reason;
  EXPECT_EQ(SqliteStore({.path = path_}).highestSequence(2), 100u);
}

TEST_F(CommitterTest, PastTheDeadlineTheyFailAsDatabaseUnavailable) {
  LedgerCommitter committer(store(), {.deadline = std::chrono::milliseconds(100)});
  std::vector<Outcome> outcomes;
  SqliteWriteLock lock(path_);
  for (std::uint64_t s = 1; s <= 20; ++s) committer.submit(makeTx(3, s));
  ASSERT_TRUE(waitForOutcomes(committer, outcomes, 20));
  for (const auto& o : outcomes) {
    EXPECT_EQ(o.status, TxStatus::Failed);
    EXPECT_EQ(o.reason.rfind("database unavailable: ", 0), 0u) << o.reason;
    EXPECT_NE(o.reason.find(path_), std::string::npos) << o.reason;
  }
  lock.release();
  EXPECT_EQ(SqliteStore({.path = path_}).counts().total, 0u);
}

// Out of pages: the batches that fit commit, the rest fail at once with "database full", and
// the file holds exactly the committed ones.
TEST_F(CommitterTest, AFullDatabaseFailsTransactionsWithTheReason) {
  LedgerCommitter committer(store(40), {.capacity = 8192, .max_batch = 64});
  const std::size_t n = 6000;
  for (std::uint64_t i = 0; i < n; ++i) {
    ASSERT_EQ(committer.submit(makeTx(1 + i % 50, 1 + i / 50)), Submit::Accepted);
  }
  std::vector<Outcome> outcomes;
  ASSERT_TRUE(waitForOutcomes(committer, outcomes, n));
  std::size_t committed = 0, full = 0;
  for (const auto& o : outcomes) {
    if (o.status == TxStatus::Committed) {
      ++committed;
    } else {
      ASSERT_EQ(o.status, TxStatus::Failed);
      EXPECT_EQ(o.reason.rfind("database full: ", 0), 0u) << o.reason;
      ++full;
    }
  }
  EXPECT_GT(committed, 0u);
  EXPECT_GT(full, 0u) << "40 pages never filled";
  committer.stop();
  EXPECT_EQ(SqliteStore({.path = path_}).counts().total, committed);
}

TEST_F(CommitterTest, StopGivesWhatCouldNotCommitAFailedOutcome) {
  LedgerCommitter committer(store(), {.deadline = std::chrono::minutes(10)});
  SqliteWriteLock lock(path_);
  for (std::uint64_t s = 1; s <= 50; ++s) committer.submit(makeTx(4, s));
  committer.stop();
  EXPECT_EQ(committer.submit(makeTx(4, 51)), Submit::Stopped);
  std::vector<Outcome> outcomes;
  committer.poll(outcomes);
  ASSERT_EQ(outcomes.size(), 50u);
  for (const auto& o : outcomes) {
    EXPECT_EQ(o.status, TxStatus::Failed);
    EXPECT_NE(o.reason.find("committer stopped"), std::string::npos) << o.reason;
  }
}

TEST_F(CommitterTest, StopCommitsWhatIsPendingWhenTheDatabaseIsUp) {
  std::vector<Outcome> outcomes;
  {
    LedgerCommitter committer(store(), {.max_batch = 7});
    for (std::uint64_t s = 1; s <= 500; ++s) committer.submit(makeTx(5, s));
    committer.stop();
    committer.poll(outcomes);
  }
  ASSERT_EQ(outcomes.size(), 500u);
  for (const auto& o : outcomes) EXPECT_EQ(o.status, TxStatus::Committed) << o.reason;
  EXPECT_EQ(SqliteStore({.path = path_}).counts().total, 500u);
}

// The leaderboard is served from its own connection: in WAL mode reading it never waits for the
// committer's writes, nor they for it.
TEST_F(CommitterTest, TheLeaderboardReadsOnItsOwnConnectionWhileTheCommitterWrites) {
  LedgerCommitter committer(store(), {.capacity = 2048, .max_batch = 8});
  SqliteStore reader({.path = path_, .busy_timeout_ms = 0});
  for (std::uint64_t i = 0; i < 1000; ++i) {
    std::uint64_t player = 1 + i % 100, seq = 1 + i / 100;
    ASSERT_EQ(committer.submit(makeScore(player, seq, std::int64_t(player * 10 + seq), i)),
              Submit::Accepted);
  }
  std::vector<Outcome> outcomes;
  std::size_t reads = 0;
  while (outcomes.size() < 1000) {
    auto board = reader.leaderboard(5);  // would throw StoreError if it had to wait
    ASSERT_LE(board.size(), 5u);
    ++reads;
    ASSERT_TRUE(waitUntil([&] { return committer.poll(outcomes) > 0 || outcomes.size() == 1000; }));
  }
  EXPECT_GT(reads, 0u);
  for (const auto& o : outcomes) EXPECT_EQ(o.status, TxStatus::Committed) << o.reason;
  // Best of player p is p*10 + 10 (seq 10), reached at tick 900 + p - 1.
  EXPECT_EQ(reader.leaderboard(3),
            (std::vector<LeaderboardRow>{{100, 1010, 999}, {99, 1000, 998}, {98, 990, 997}}));
}

}  // namespace
}  // namespace zonesim::ledger::test
