// The zone's end of the players' transaction channels against a real DDS link on a private
// domain (the test's writer and reader play the gateway) and a real SQLite ledger: in sequence
// order and once whatever order and how many copies arrive; a repeat answered, not stored
// again; a zone that took the avatar over (a handoff, a restart) answers a repeat through the
// ledger's key; a transaction for an avatar elsewhere dropped and counted; a zone without a
// ledger tells the client why.
#include "zone_node/transactions.h"

#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <thread>

#include "idl/dds_take.h"
#include "ledger/temp_dir.h"
#include "player_zone_fixture.h"
#include "zone_node/cluster/migration.h"

namespace zonesim::zone {
namespace {

constexpr std::uint64_t kPlayer = (std::uint64_t{3} << 32) | 11;

struct Answer {
  std::uint8_t status;
  std::string reason;
};

class TransactionsTest : public PlayerZoneTest {
 protected:
  TransactionsTest()
      : players_(scene_, 0, 1),
        transactions_(dds::makePartitionWriter(gateway_.get(), topics_.player_transactions.get(),
                                               dds::zonePartition(0), keep_all_.get())),
        outcomes_(dds::makePartitionReader(gateway_.get(), topics_.transaction_outcomes.get(), "",
                                           keep_all_.get())) {}

  std::unique_ptr<ledger::LedgerCommitter> committer() {
    return std::make_unique<ledger::LedgerCommitter>(
        ledger::openStore({.backend = "sqlite", .target = dir_.file("ledger.db")}));
  }
  // One tick: input, then the outcomes; 5 ms of wall time for DDS and the committer.
  void tick(Transactions& t) {
    ++tick_;
    PlayerZone z = zone();
    players_.input(z);
    MigrationResult none;
    players_.migrated(z, none);
    t.input(z);
    t.publish(z);
    dds::takeAll<zonesim_dds_TransactionOutcome>(
        outcomes_.reader.get(), [&](const zonesim_dds_TransactionOutcome& o) {
          if (o.player_id == kPlayer) answers_.emplace(o.seq, Answer{o.status, o.reason});
          ++answered_;
        });
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  template <typename F>
  bool tickUntil(Transactions& t, F&& done) {
    for (int i = 0; i < 2000; ++i) {
      tick(t);
      if (done()) return true;
    }
    return false;
  }
  void spawnAvatar(Transactions& t) {
    requestSpawn(kPlayer, 1);
    ASSERT_TRUE(tickUntil(t, [&] { return store_.avatarOf(kPlayer).has_value(); }));
  }
  void send(std::uint32_t seq, std::uint64_t player = kPlayer, std::uint32_t decided = 0) {
    zonesim_dds_PlayerTransaction m{};
    m.player_id = player;
    m.seq = seq;
    m.decided = decided;
    m.kind = 2;  // loot
    m.item = 100 + seq;
    m.amount = 1;
    dds::check(dds_write(transactions_.writer.get(), &m), "write PlayerTransaction");
  }
  std::uint64_t storedRows() {
    return ledger::openStore({.backend = "sqlite", .target = dir_.file("ledger.db")})->counts().total;
  }
  std::uint32_t lastHandedOver() const {
    return store_.avatar[*store_.avatarOf(kPlayer)].last_transaction_seq;
  }

  ledger::test::TempDir dir_;
  Players players_;
  dds::PartitionWriter transactions_;
  dds::PartitionReader outcomes_;
  std::map<std::uint32_t, Answer> answers_;  // the first answer per seq
  std::uint64_t answered_ = 0;
};

TEST_F(TransactionsTest, OutOfOrderAndRepeatedCopiesAreStoredOnceInOrder) {
  Transactions t(committer());
  spawnAvatar(t);
  for (std::uint32_t seq : {3u, 1u, 1u, 2u}) send(seq);
  ASSERT_TRUE(tickUntil(t, [&] { return answers_.size() == 3; })) << answers_.size();
  // 5 comes while 4 is missing: the newest outcome (3's) is repeated, the client's cue to send
  // 4 again at once.
  std::uint64_t before = answered_;
  send(5);
  ASSERT_TRUE(tickUntil(t, [&] { return answered_ > before; }));
  EXPECT_EQ(t.counters().gap_notices, 1u);
  EXPECT_EQ(answers_.count(5), 0u) << "held for 4";
  send(2);
  send(4);
  ASSERT_TRUE(tickUntil(t, [&] { return answers_.size() == 5; })) << answers_.size();
  for (std::uint32_t seq = 1; seq <= 5; ++seq)
    EXPECT_EQ(answers_[seq].status, std::uint8_t(ledger::TxStatus::Committed)) << "seq " << seq;
  EXPECT_EQ(lastHandedOver(), 5u);
  EXPECT_EQ(t.counters().committed, 5u);
  EXPECT_EQ(t.counters().submitted, 5u) << "each handed to the ledger once";
  EXPECT_EQ(storedRows(), 5u);
  // A copy of a decided one (its outcome was lost) is answered from memory, not stored again.
  EXPECT_GE(t.counters().answered_again, 1u) << "the second copy of 2";
  std::uint64_t again = t.counters().answered_again;
  before = answered_;
  send(2);
  ASSERT_TRUE(tickUntil(t, [&] { return answered_ > before; }));
  EXPECT_EQ(t.counters().answered_again, again + 1);
  EXPECT_EQ(t.counters().submitted, 5u);
  EXPECT_EQ(storedRows(), 5u);
}

TEST_F(TransactionsTest, AZoneThatTookTheAvatarOverAnswersARepeatThroughTheLedger) {
  {
    Transactions first(committer());
    spawnAvatar(first);
    for (std::uint32_t seq = 1; seq <= 3; ++seq) send(seq);
    ASSERT_TRUE(tickUntil(first, [&] { return answers_.size() == 3; }));
  }
  // The avatar, with its last handed-over sequence, now lives in a zone with no memory of
  // the outcomes (as after a handoff, or a restart from a checkpoint).
  ASSERT_EQ(lastHandedOver(), 3u);
  answers_.clear();
  Transactions next(committer());
  send(3);  // the client never heard 3's outcome
  send(4);
  ASSERT_TRUE(tickUntil(next, [&] { return answers_.size() == 2; }));
  EXPECT_EQ(answers_[3].status, std::uint8_t(ledger::TxStatus::AlreadyCommitted));
  EXPECT_EQ(answers_[4].status, std::uint8_t(ledger::TxStatus::Committed));
  EXPECT_EQ(next.counters().resubmitted, 1u);
  EXPECT_EQ(storedRows(), 4u) << "3 is stored once";
}

// Restored from a checkpoint older than what the client was told: the client's decided point
// says where to go on, since nothing up to it is sent again.
TEST_F(TransactionsTest, ARestoredZoneGoesOnFromTheClientsDecidedPoint) {
  Transactions t(committer());
  spawnAvatar(t);
  store_.avatar[*store_.avatarOf(kPlayer)].last_transaction_seq = 2;  // the checkpoint's
  send(6, kPlayer, 5);  // the client had outcomes up to 5 from the zone before the crash
  ASSERT_TRUE(tickUntil(t, [&] { return answers_.size() == 1; }));
  EXPECT_EQ(answers_[6].status, std::uint8_t(ledger::TxStatus::Committed));
  EXPECT_EQ(lastHandedOver(), 6u);
  EXPECT_EQ(t.counters().fast_forwards, 1u);
}

TEST_F(TransactionsTest, OneForAnAvatarElsewhereIsDroppedAndCounted) {
  Transactions t(committer());
  spawnAvatar(t);
  send(1, kPlayer + 1);  // a player whose avatar is in another zone
  send(1);
  ASSERT_TRUE(tickUntil(t, [&] { return answers_.size() == 1; }));
  EXPECT_EQ(t.counters().not_here, 1u);
  EXPECT_EQ(answered_, 1u) << "no answer for the other player: its client sends it again";
}

TEST_F(TransactionsTest, AZoneWithoutALedgerTellsTheClientWhy) {
  Transactions t(nullptr);
  spawnAvatar(t);
  send(1);
  ASSERT_TRUE(tickUntil(t, [&] { return answers_.size() == 1; }));
  EXPECT_EQ(answers_[1].status, std::uint8_t(ledger::TxStatus::Failed));
  EXPECT_NE(answers_[1].reason.find("--ledger"), std::string::npos) << answers_[1].reason;
  EXPECT_EQ(t.counters().failed, 1u);
}

}  // namespace
}  // namespace zonesim::zone
