// Ack bookkeeping of the gateway -> client stream: the client's window (acked, duplicate,
// reordered, too old) and the gateway's per-entity resend decisions (acked, lost, superseded).
#include "wire/ack_window.h"

#include <gtest/gtest.h>

#include <vector>

namespace zonesim::gateway {
namespace {

constexpr std::int64_t kMs = 1'000'000;

TEST(AckWindow, InOrderSetsBitsBelowHighest) {
  AckWindow w;
  for (std::uint32_t s = 1; s <= 5; ++s) EXPECT_TRUE(w.receive(s));
  EXPECT_EQ(w.ack(), 5u);
  EXPECT_EQ(w.bits(), 0b1111u);  // 4, 3, 2, 1
}

TEST(AckWindow, LossLeavesAHoleAndReorderFillsIt) {
  AckWindow w;
  EXPECT_TRUE(w.receive(1));
  EXPECT_TRUE(w.receive(3));  // 2 lost so far
  EXPECT_EQ(w.ack(), 3u);
  EXPECT_EQ(w.bits(), 0b10u);  // 2 missing, 1 present
  EXPECT_TRUE(w.receive(2));   // late, reordered
  EXPECT_EQ(w.bits(), 0b11u);
}

TEST(AckWindow, DuplicatesAndAncientAreRefused) {
  AckWindow w;
  EXPECT_TRUE(w.receive(40));
  EXPECT_FALSE(w.receive(40));
  EXPECT_TRUE(w.receive(39));
  EXPECT_FALSE(w.receive(39));
  EXPECT_TRUE(w.receive(8));    // exactly 32 back: still tracked (bit 31)
  EXPECT_FALSE(w.receive(7));   // beyond the window
  EXPECT_FALSE(w.receive(0));   // unnumbered is never acked
  EXPECT_TRUE(w.receive(100));  // a jump past the window forgets the old bits
  EXPECT_EQ(w.bits(), 0u);
  EXPECT_TRUE(w.receive(68));
  EXPECT_EQ(w.bits(), 1u << 31);
}

std::vector<std::uint64_t> ids(std::initializer_list<std::uint64_t> l) {
  return l;
}

TEST(ResendTracker, AckedEntitiesAreNotResent) {
  ResendTracker t(0.05, 1.0);
  auto a = ids({1, 2});
  std::uint32_t s = t.nextSeq();
  t.sent(s, a, Carried::Update, 0);
  EXPECT_EQ(t.pending(), 2u);
  t.onAck(s, 0, 20 * kMs);
  EXPECT_EQ(t.pending(), 0u);
  EXPECT_TRUE(t.due(10'000 * kMs).empty());
  EXPECT_EQ(t.acked(), 1u);
}

TEST(ResendTracker, LostDatagramIsResentAfterTimeoutOnly) {
  ResendTracker t(0.05, 1.0);
  std::uint32_t s1 = t.nextSeq(), s2 = t.nextSeq();
  auto spawn = ids({7}), update = ids({9});
  t.sent(s1, spawn, Carried::Spawn, 0);
  t.sent(s2, update, Carried::Update, 0);
  t.onAck(s2, 0, 40 * kMs);  // s1 lost: bit 0 (seq 1) clear
  EXPECT_TRUE(t.spawnPending(7));
  EXPECT_FALSE(t.spawnPending(9));
  std::int64_t rto = t.rtoNs();
  EXPECT_GE(rto, 50 * kMs);
  // Both went out in the same tick: s2's ack does not prove s1 lost (reordered, maybe).
  EXPECT_TRUE(t.due(rto - 1, LossDetection::LaterAck).empty());
  EXPECT_TRUE(t.due(rto - 1, LossDetection::Timeout).empty());
  ResendDue d = t.due(rto, LossDetection::Timeout);
  EXPECT_EQ(d.spawns, ids({7}));
  EXPECT_TRUE(d.updates.empty() && d.despawns.empty());
}

TEST(ResendTracker, SkippedScansMissNothingThatComesDue) {
  // due() skips its scan while nothing pending can have timed out; the bound it keeps must
  // follow sends, acks and resends without hiding an entity that is due.
  ResendTracker t(0.05, 0.05);  // rto fixed at 50 ms
  std::uint32_t s1 = t.nextSeq();
  t.sent(s1, ids({1}), Carried::Update, 0);
  EXPECT_TRUE(t.due(49 * kMs).empty());
  EXPECT_EQ(t.due(50 * kMs).updates, ids({1}));
  t.onAck(s1, 0, 60 * kMs);
  EXPECT_TRUE(t.due(200 * kMs).empty());  // a scan: nothing pending, nothing due
  std::uint32_t s2 = t.nextSeq();
  t.sent(s2, ids({2}), Carried::Update, 300 * kMs);
  EXPECT_TRUE(t.due(340 * kMs).empty());
  std::uint32_t s3 = t.nextSeq();
  t.sent(s3, ids({3}), Carried::Spawn, 330 * kMs);
  EXPECT_EQ(t.due(350 * kMs).updates, ids({2}));
  EXPECT_TRUE(t.due(350 * kMs).spawns.empty());
  // The same into a reused result, cleared first.
  ResendDue d;
  d.despawns = ids({42});
  t.due(380 * kMs, LossDetection::Timeout, d);
  EXPECT_EQ(d.updates, ids({2}));
  EXPECT_EQ(d.spawns, ids({3}));
  EXPECT_TRUE(d.despawns.empty());
  // Overtaken: a later datagram's ack marks an earlier one lost before its timeout.
  ResendTracker u(0.05, 0.05);
  std::uint32_t a = u.nextSeq(), b = u.nextSeq();
  u.sent(a, ids({5}), Carried::Update, 0);
  u.sent(b, ids({6}), Carried::Update, 10 * kMs);
  u.onAck(b, 0, 20 * kMs);
  EXPECT_TRUE(u.due(25 * kMs, LossDetection::Timeout).empty());
  EXPECT_EQ(u.due(25 * kMs, LossDetection::LaterAck).updates, ids({5}));
}

TEST(ResendTracker, AnAckOfALaterTicksDatagramMarksEarlierOnesLost) {
  ResendTracker t(0.05, 1.0);
  auto lost = ids({4, 6}), later = ids({5});
  std::uint32_t s1 = t.nextSeq();
  t.sent(s1, lost, Carried::Update, 0);
  std::uint32_t s2 = t.nextSeq();
  t.sent(s2, later, Carried::Update, 33 * kMs);  // the next tick
  constexpr auto kEarly = LossDetection::LaterAck;
  EXPECT_TRUE(t.due(34 * kMs, kEarly).empty());  // nothing acknowledged yet: wait
  t.onAck(s2, 0, 36 * kMs);                      // s2 arrived, s1 (bit 0) did not
  EXPECT_LT(36 * kMs, t.rtoNs());
  EXPECT_EQ(t.due(36 * kMs, kEarly).updates, ids({4, 6}));       // at once
  EXPECT_TRUE(t.due(36 * kMs, LossDetection::Timeout).empty());  // the default rule waits
  // A resend goes out in a new datagram: it is not presumed lost until a later one is acked.
  std::uint32_t s3 = t.nextSeq();
  t.sent(s3, lost, Carried::Update, 40 * kMs);
  EXPECT_TRUE(t.due(41 * kMs, kEarly).empty());
  t.onAck(s3, 0b10, 60 * kMs);
  EXPECT_EQ(t.pending(), 0u);
}

TEST(ResendTracker, OnlyTheNewestCarrierSettlesAnEntity) {
  ResendTracker t(0.05, 1.0);
  auto e = ids({5});
  std::uint32_t old_seq = t.nextSeq();
  t.sent(old_seq, e, Carried::Update, 0);
  std::uint32_t new_seq = t.nextSeq();
  t.sent(new_seq, e, Carried::Update, 10 * kMs);
  t.onAck(old_seq, 0, 30 * kMs);  // the older state arrived; the newer may be lost
  EXPECT_EQ(t.pending(), 1u);
  ResendDue d = t.due(10 * kMs + t.rtoNs());
  EXPECT_EQ(d.updates, ids({5}));
  t.onAck(new_seq, 1, 40 * kMs);  // bit 0 re-acks old_seq: harmless
  EXPECT_EQ(t.pending(), 0u);
  EXPECT_EQ(t.acked(), 2u);
}

TEST(ResendTracker, AnAckOfAnEarlierSpawnOfTheRunEndsTheSpawnButNotTheNewestState) {
  // An entity that changes every tick goes as a Spawn while its spawn is unacknowledged; each
  // tick's Spawn is sent before the last one's ack returns.
  ResendTracker t(0.05, 1.0);
  auto e = ids({8});
  std::uint32_t s1 = t.nextSeq(), s2 = t.nextSeq();
  t.sent(s1, e, Carried::Spawn, 0);
  t.sent(s2, e, Carried::Spawn, 33 * kMs);
  t.onAck(s1, 0, 50 * kMs);
  EXPECT_FALSE(t.spawnPending(8)) << "the client holds it: its next state is an update";
  EXPECT_EQ(t.pending(), 1u) << "the newest state is still in flight";
  ResendDue d = t.due(33 * kMs + t.rtoNs());
  EXPECT_EQ(d.updates, ids({8}));
  EXPECT_TRUE(d.spawns.empty());

  // A Spawn from before a despawn says nothing about the entity's new spawn.
  auto f = ids({9});
  std::uint32_t a = t.nextSeq(), b = t.nextSeq(), c = t.nextSeq();
  t.sent(a, f, Carried::Spawn, 100 * kMs);
  t.sent(b, f, Carried::Despawn, 133 * kMs);
  t.sent(c, f, Carried::Spawn, 166 * kMs);
  t.onAck(a, 0, 180 * kMs);
  EXPECT_TRUE(t.spawnPending(9));
}

TEST(ResendTracker, DespawnSupersedesSpawnAndDuplicateAcksCountOnce) {
  ResendTracker t(0.05, 1.0);
  auto e = ids({3});
  std::uint32_t s1 = t.nextSeq();
  t.sent(s1, e, Carried::Spawn, 0);
  std::uint32_t s2 = t.nextSeq();
  t.sent(s2, e, Carried::Despawn, 5 * kMs);
  EXPECT_FALSE(t.spawnPending(3));
  t.onAck(s1, 0, 20 * kMs);
  t.onAck(s1, 0, 21 * kMs);  // duplicate ack
  EXPECT_EQ(t.acked(), 1u);
  EXPECT_EQ(t.due(5 * kMs + t.rtoNs()).despawns, ids({3}));
  t.onAck(s2, 0b1, 30 * kMs);
  EXPECT_EQ(t.pending(), 0u);
}

TEST(ResendTracker, AcksBeyondWhatWasSentAreIgnored) {
  ResendTracker t(0.05, 1.0);
  auto e = ids({1});
  std::uint32_t s = t.nextSeq();
  t.sent(s, e, Carried::Update, 0);
  t.onAck(s + 1, 0xFFFFFFFFu, 10 * kMs);  // forged: seq s + 1 was never sent
  EXPECT_EQ(t.pending(), 1u);
  t.onAck(0, 0xFFFFFFFFu, 10 * kMs);
  EXPECT_EQ(t.pending(), 1u);
}

TEST(ResendTracker, TimeoutFollowsMeasuredRoundTripWithinBounds) {
  ResendTracker t(0.05, 1.0);
  auto e = ids({1});
  for (int i = 0; i < 50; ++i) {
    std::uint32_t s = t.nextSeq();
    t.sent(s, e, Carried::Update, i * 1000 * kMs);
    t.onAck(s, 0, i * 1000 * kMs + 200 * kMs);  // a steady 200 ms round trip
  }
  EXPECT_NEAR(double(t.rtoNs()) / kMs, 200.0, 5.0);  // variance decays towards zero
  ResendTracker slow(0.05, 1.0);
  std::uint32_t s = slow.nextSeq();
  slow.sent(s, e, Carried::Update, 0);
  slow.onAck(s, 0, 5000 * kMs);
  EXPECT_EQ(slow.rtoNs(), 1000 * kMs);  // capped
}

}  // namespace
}  // namespace zonesim::gateway
