// The cases every back end passes: commit, idempotent retry after a crash, conflicts, repeats
// within a batch, invalid transactions, the leaderboard's order and ties, the resume sequence.

#include "store_conformance.h"

#include <sys/wait.h>
#include <unistd.h>

#include <vector>

namespace zonesim::ledger::test {

Transaction makeTx(std::uint64_t player, std::uint64_t seq, Kind kind) {
  Transaction tx;
  tx.player = player;
  tx.seq = seq;
  tx.kind = kind;
  tx.item = 1000 + seq % 7;
  tx.amount = std::int64_t(seq % 5 + 1);
  tx.tick = 10 * seq;
  if (kind == Kind::Trade) tx.counterparty = player + 1;
  if (kind == Kind::Purchase) tx.price = 25;
  if (kind == Kind::Score) tx.score = std::int64_t(seq * 3);
  return tx;
}

Transaction makeScore(std::uint64_t player, std::uint64_t seq, std::int64_t score,
                      std::uint64_t tick) {
  Transaction tx = makeTx(player, seq, Kind::Score);
  tx.score = score;
  tx.tick = tick;
  return tx;
}

namespace {

std::vector<TxStatus> statuses(const std::vector<TxResult>& results) {
  std::vector<TxStatus> out;
  for (const auto& r : results) out.push_back(r.status);
  return out;
}

std::vector<Transaction> mixedBatch(std::uint64_t players, std::uint64_t per_player) {
  const Kind kinds[] = {Kind::Trade, Kind::Loot, Kind::Purchase, Kind::Score};
  std::vector<Transaction> batch;
  for (std::uint64_t p = 1; p <= players; ++p) {
    for (std::uint64_t s = 1; s <= per_player; ++s) batch.push_back(makeTx(p, s, kinds[s % 4]));
  }
  return batch;
}

TEST_P(StoreConformance, CommitsABatchAndCountsItByKind) {
  auto batch = mixedBatch(3, 8);  // seq 1..8: kinds loot, purchase, score, trade, ...
  auto results = store_->commit(batch);
  ASSERT_EQ(results.size(), batch.size());
  for (const auto& r : results) EXPECT_EQ(r.status, TxStatus::Committed) << r.reason;
  LedgerCounts counts = store_->counts();
  EXPECT_EQ(counts.total, 24u);
  EXPECT_EQ(counts.of(Kind::Trade), 6u);
  EXPECT_EQ(counts.of(Kind::Loot), 6u);
  EXPECT_EQ(counts.of(Kind::Purchase), 6u);
  EXPECT_EQ(counts.of(Kind::Score), 6u);
  EXPECT_TRUE(store_->commit({}).empty());
}

// A process that committed half of its transactions and died without closing anything; the
// retry of the whole batch from a new connection applies the other half only.
TEST_P(StoreConformance, RetryAfterACrashAppliesOnce) {
  auto batch = mixedBatch(4, 25);
  const std::size_t half = batch.size() / 2;
  pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    int code = 1;
    try {
      auto store = harness_->open();
      auto results = store->commit(std::span(batch).first(half));
      code = results.size() == half && results.back().status == TxStatus::Committed ? 0 : 2;
    } catch (...) {
      code = 3;
    }
    _exit(code);  // no destructors: nothing closed, the WAL not checkpointed
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "child status " << status;

  store_.reset();
  store_ = harness_->open();
  auto results = store_->commit(batch);
  ASSERT_EQ(results.size(), batch.size());
  for (std::size_t i = 0; i < batch.size(); ++i) {
    EXPECT_EQ(results[i].status, i < half ? TxStatus::AlreadyCommitted : TxStatus::Committed)
        << describe(batch[i]) << ": " << results[i].reason;
  }
  EXPECT_EQ(store_->counts().total, batch.size());
  for (const auto& r : store_->commit(batch)) EXPECT_EQ(r.status, TxStatus::AlreadyCommitted);
  EXPECT_EQ(store_->counts().total, batch.size());
}

TEST_P(StoreConformance, ADifferentTransactionUnderAStoredKeyIsAConflict) {
  Transaction stored = makeTx(7, 3, Kind::Purchase);
  ASSERT_EQ(store_->commit({&stored, 1})[0].status, TxStatus::Committed);
  Transaction other = stored;
  other.amount += 40;
  other.price = 99;
  auto results = store_->commit({&other, 1});
  EXPECT_EQ(results[0].status, TxStatus::Conflict);
  EXPECT_NE(results[0].reason.find("player 7 seq 3"), std::string::npos) << results[0].reason;
  EXPECT_NE(results[0].reason.find("amount"), std::string::npos) << results[0].reason;
  EXPECT_NE(results[0].reason.find("price 25 stored, 99 sent"), std::string::npos)
      << results[0].reason;
  // The stored one stays: it is still a duplicate of itself, and nothing was added.
  EXPECT_EQ(store_->commit({&stored, 1})[0].status, TxStatus::AlreadyCommitted);
  EXPECT_EQ(store_->counts().total, 1u);
}

// A zone that takes the avatar over after a handoff or a restart applies the resent
// transaction at another tick: the same request, stored once, with its first tick.
TEST_P(StoreConformance, ARetryAtAnotherTickIsAlreadyCommitted) {
  Transaction first = makeTx(9, 4, Kind::Loot);
  ASSERT_EQ(store_->commit({&first, 1})[0].status, TxStatus::Committed);
  Transaction retry = first;
  retry.tick += 500;
  auto results = store_->commit({&retry, 1});
  EXPECT_EQ(results[0].status, TxStatus::AlreadyCommitted) << results[0].reason;
  EXPECT_EQ(store_->counts().total, 1u);
  EXPECT_EQ(store_->highestSequence(9), 4u);
}

TEST_P(StoreConformance, TheFirstOfAKeyWithinABatchDecides) {
  Transaction a = makeTx(5, 1, Kind::Loot);
  Transaction changed = a;
  changed.item += 1;
  Transaction b = makeTx(5, 2, Kind::Loot);
  std::vector<Transaction> batch{a, a, changed, b, changed};
  EXPECT_EQ(statuses(store_->commit(batch)),
            (std::vector<TxStatus>{TxStatus::Committed, TxStatus::AlreadyCommitted,
                                   TxStatus::Conflict, TxStatus::Committed, TxStatus::Conflict}));
  // Now the key is stored as `a`: a batch led by `changed` conflicts, and `a` after it is a
  // duplicate of what is stored.
  std::vector<Transaction> again{changed, a};
  EXPECT_EQ(statuses(store_->commit(again)),
            (std::vector<TxStatus>{TxStatus::Conflict, TxStatus::AlreadyCommitted}));
  EXPECT_EQ(store_->counts().total, 2u);
}

TEST_P(StoreConformance, AnInvalidTransactionFailsAloneInItsBatch) {
  Transaction zero_seq = makeTx(1, 0);
  Transaction self_trade = makeTx(2, 1, Kind::Trade);
  self_trade.counterparty = 2;
  Transaction too_big = makeTx(std::uint64_t(1) << 63, 1);
  std::vector<Transaction> batch{makeTx(1, 1), zero_seq, self_trade, too_big, makeTx(1, 2)};
  auto results = store_->commit(batch);
  EXPECT_EQ(statuses(results),
            (std::vector<TxStatus>{TxStatus::Committed, TxStatus::Failed, TxStatus::Failed,
                                   TxStatus::Failed, TxStatus::Committed}));
  EXPECT_NE(results[1].reason.find("sequence"), std::string::npos) << results[1].reason;
  EXPECT_NE(results[2].reason.find("counterparty"), std::string::npos) << results[2].reason;
  EXPECT_NE(results[3].reason.find("player id"), std::string::npos) << results[3].reason;
  EXPECT_EQ(store_->counts().total, 2u);
}

TEST_P(StoreConformance, KeysUpToTheSignedLimitRoundTrip) {
  const std::uint64_t top = (std::uint64_t(1) << 63) - 1;
  Transaction tx = makeScore(top, top, -5, top);
  tx.item = top;
  ASSERT_EQ(store_->commit({&tx, 1})[0].status, TxStatus::Committed);
  EXPECT_EQ(store_->highestSequence(top), top);
  EXPECT_EQ(store_->commit({&tx, 1})[0].status, TxStatus::AlreadyCommitted);
  auto board = store_->leaderboard(10);
  ASSERT_EQ(board.size(), 1u);
  EXPECT_EQ(board[0], (LeaderboardRow{top, -5, top}));
}

// Best score per player; equal scores go to the earlier tick, then the lower player id;
// trades, loot and purchases are not on it.
TEST_P(StoreConformance, LeaderboardOrdersByBestScoreThenTickThenPlayer) {
  std::vector<Transaction> batch{
      makeScore(10, 1, 500, 90),  makeScore(10, 2, 800, 120),  // player 10's best: 800 at 120
      makeScore(11, 1, 800, 100),                              // 800 earlier: ahead of 10
      makeScore(12, 1, 800, 120),                              // ties 10 fully: id decides
      makeScore(13, 1, 900, 300), makeScore(13, 2, 900, 200),  // first reached at 200
      makeScore(14, 1, -20, 5),   makeTx(15, 1, Kind::Purchase), makeTx(16, 1, Kind::Trade)};
  for (const auto& r : store_->commit(batch)) ASSERT_EQ(r.status, TxStatus::Committed);
  const std::vector<LeaderboardRow> expected{
      {13, 900, 200}, {11, 800, 100}, {10, 800, 120}, {12, 800, 120}, {14, -20, 5}};
  EXPECT_EQ(store_->leaderboard(10), expected);
  EXPECT_EQ(store_->leaderboard(3),
            std::vector<LeaderboardRow>(expected.begin(), expected.begin() + 3));
  EXPECT_TRUE(store_->leaderboard(0).empty());
}

TEST_P(StoreConformance, HighestSequenceIsWhereAResumedPlayerGoesOn) {
  EXPECT_EQ(store_->highestSequence(42), 0u);
  std::vector<Transaction> batch{makeTx(42, 1), makeTx(42, 2), makeTx(42, 5), makeTx(43, 9)};
  store_->commit(batch);
  EXPECT_EQ(store_->highestSequence(42), 5u);
  EXPECT_EQ(store_->highestSequence(43), 9u);
  store_.reset();
  store_ = harness_->open();
  EXPECT_EQ(store_->highestSequence(42), 5u);
  EXPECT_EQ(store_->counts().total, 4u);
}

}  // namespace
}  // namespace zonesim::ledger::test
