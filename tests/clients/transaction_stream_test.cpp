// A player's transaction channel on a virtual clock: it makes transactions at its rate and
// numbers them from 1, resends each until its outcome comes, counts every outcome once, moves
// its window on only past sequences decided without a gap, resends the oldest undecided one at
// once on a repeated outcome (the zone's duplicate ack), and refuses to make more than its
// window holds.
#include "clients/transaction_stream.h"

#include <gtest/gtest.h>

#include <vector>

namespace zonesim::clients {
namespace {

constexpr std::int64_t kMs = 1'000'000;
constexpr std::uint8_t kCommitted = 0, kAlreadyCommitted = 1, kFailed = 3;

struct Wire {
  std::vector<gateway::TransactionInfo> sent;
  std::function<void(const gateway::TransactionInfo&)> send() {
    return [this](const gateway::TransactionInfo& t) { sent.push_back(t); };
  }
  std::vector<std::uint32_t> seqs() const {
    std::vector<std::uint32_t> s;
    for (const auto& t : sent) s.push_back(t.seq);
    return s;
  }
};

TEST(TransactionStream, MakesAtItsRateNumberedFromOneWithValidContent) {
  TransactionStream s(10, 1, 0);
  Wire w;
  for (std::int64_t t = 0; t <= 1000 * kMs; t += 10 * kMs) s.due(t, w.send());
  EXPECT_EQ(s.counters().made, 10u);
  EXPECT_EQ(s.counters().sent, 10u);
  EXPECT_GT(s.counters().resent, 0u) << "no outcomes came: each goes again after its timeout";
  std::vector<gateway::TransactionInfo> firsts;
  for (const auto& t : w.sent)
    if (firsts.empty() || t.seq > firsts.back().seq) firsts.push_back(t);
  w.sent = firsts;
  ASSERT_EQ(w.sent.size(), 10u);
  for (std::size_t i = 0; i < w.sent.size(); ++i) {
    const gateway::TransactionInfo& t = w.sent[i];
    EXPECT_EQ(t.seq, i + 1);
    EXPECT_TRUE(t.kind >= 2 && t.kind <= 4) << int(t.kind);
    if (t.kind != 4) {
      EXPECT_GE(t.item, 1u);
    }
  }
  EXPECT_FALSE(TransactionStream(0, 1, 0).active());
}

TEST(TransactionStream, ResendsUntilItsOutcomeAndCountsEachOutcomeOnce) {
  TransactionStream s(1, 2, 0);  // one a second: the first at a random phase within it
  Wire w;
  std::int64_t t = 0;
  while (w.sent.empty()) s.due(t += kMs, w.send());
  std::int64_t first = t;
  s.due(first + 240 * kMs, w.send());
  EXPECT_EQ(w.sent.size(), 1u) << "not before the initial timeout of 250 ms";
  s.due(first + 250 * kMs, w.send());
  ASSERT_EQ(w.sent.size(), 2u);
  EXPECT_EQ(w.sent[1], w.sent[0]) << "the same transaction again";
  EXPECT_EQ(s.counters().resent, 1u);
  s.onOutcome(1, kAlreadyCommitted, first + 300 * kMs);
  s.onOutcome(1, kCommitted, first + 310 * kMs);  // the answer to the first copy, late
  EXPECT_EQ(s.counters().committed, 1u);
  EXPECT_EQ(s.counters().already_committed, 1u);
  EXPECT_EQ(s.counters().outcome_repeats, 1u);
  EXPECT_EQ(s.pending(), 0u);
  EXPECT_EQ(s.counters().latency_ms.max(), 300.0);
  s.onOutcome(7, kCommitted, first + 320 * kMs);
  EXPECT_EQ(s.counters().outcome_unknown, 1u);
  std::size_t before = w.sent.size();
  s.due(first + 900 * kMs, w.send());
  EXPECT_EQ(w.sent.size(), before) << "nothing undecided to resend";
}

TEST(TransactionStream, ARepeatedOutcomeResendsTheOldestUndecidedAtOnce) {
  TransactionStream s(100, 3, 0);  // one each 10 ms
  Wire w;
  for (std::int64_t t = 0; t <= 35 * kMs; t += kMs) s.due(t, w.send());
  ASSERT_GE(w.sent.size(), 3u);
  std::int64_t now = 40 * kMs;
  s.onOutcome(1, kCommitted, now);
  w.sent.clear();
  // Number 2 was lost; the zone holds 3 and repeats 1's outcome. Before any round trip was
  // learnt, "a round trip" is half the initial timeout: 125 ms after 2 was sent.
  s.onOutcome(1, kCommitted, 200 * kMs);
  s.due(200 * kMs, w.send());
  std::vector<std::uint32_t> resent = w.seqs();
  ASSERT_FALSE(resent.empty());
  EXPECT_EQ(resent.front(), 2u) << "the oldest undecided, before its timeout";
  EXPECT_EQ(s.counters().failed, 0u);
}

TEST(TransactionStream, AFullWindowRefusesToMakeMoreAndAStartOverFailsWhatWasPending) {
  TransactionStream s(1000, 4, 0);
  Wire w;
  for (std::int64_t t = 0; t <= 100 * kMs; t += kMs) s.due(t, w.send());
  EXPECT_EQ(s.pending(), 64u) << "the window";
  EXPECT_GT(s.counters().refused_window_full, 0u);
  EXPECT_EQ(s.counters().made, 64u);
  // Outcomes for 1..10 make room for ten more.
  for (std::uint32_t q = 1; q <= 10; ++q) s.onOutcome(q, kCommitted, 101 * kMs);
  for (std::int64_t t = 101 * kMs; t <= 120 * kMs; t += kMs) s.due(t, w.send());
  EXPECT_EQ(s.counters().made, 74u);
  EXPECT_EQ(s.pending(), 64u);
  s.onOutcome(11, kFailed, 121 * kMs);
  EXPECT_EQ(s.counters().failed, 1u);
  s.restart(130 * kMs);
  EXPECT_EQ(s.pending(), 0u);
  EXPECT_EQ(s.counters().failed, 1u + 63u) << "the undecided are lost with the old player";
  w.sent.clear();
  s.due(131 * kMs, w.send());
  ASSERT_FALSE(w.sent.empty());
  EXPECT_EQ(w.sent.front().seq, 1u) << "a new player numbers from 1 again";
}

}  // namespace
}  // namespace zonesim::clients
