// The gateway's one timeline across cluster epochs, and the input history a restart resends.
#include "gateway/epoch_timeline.h"

#include <gtest/gtest.h>

#include <vector>

#include "wire/input_history.h"

namespace zonesim::gateway {
namespace {

TEST(EpochTimeline, EpochZeroMapsOntoItself) {
  EpochTimeline t(0.05);
  auto a = t.map(0, 100, 5.0);
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->tick, 100u);
  EXPECT_DOUBLE_EQ(a->sim_time, 5.0);
  EXPECT_EQ(t.epochsEntered(), 0u);
}

TEST(EpochTimeline, ANewEpochContinuesAfterTheNewestMappedAndKeepsItsOwnSpacing) {
  EpochTimeline t(0.05);
  t.map(0, 400, 20.0);
  // Restored at tick 300: it maps just after 400 and runs on one to one.
  auto first = t.map(1, 300, 15.0);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->tick, 401u);
  EXPECT_DOUBLE_EQ(first->sim_time, 20.05);
  auto later = t.map(1, 310, 15.5);
  EXPECT_EQ(later->tick, 411u);
  EXPECT_DOUBLE_EQ(later->sim_time, 20.55);
  EXPECT_EQ(t.epoch(), 1u);
  EXPECT_EQ(t.epochsEntered(), 1u);
}

TEST(EpochTimeline, SamplesOfAnOlderEpochAreDroppedAndCounted) {
  EpochTimeline t(0.05);
  t.map(0, 400, 20.0);
  t.mapTick(2, 100);  // an ownership event may open an epoch: its ticks map too
  EXPECT_FALSE(t.map(1, 500, 25.0).has_value());
  EXPECT_FALSE(t.mapTick(0, 401).has_value());
  EXPECT_EQ(t.stale(), 2u);
  // Its first sample with a sim time sets the epoch's sim offset.
  auto s = t.map(2, 101, 5.0);
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->tick, 402u);
  EXPECT_DOUBLE_EQ(s->sim_time, 20.05);
}

// A gateway started after the zones restarted (or restarted itself) has told no client any
// tick: it takes the epoch it first hears of as it comes, and still follows later restarts.
TEST(EpochTimeline, TheFirstEpochHeardOfMapsOntoItself) {
  EpochTimeline t(0.05);
  auto a = t.map(3, 900, 45.0);
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->tick, 900u);
  EXPECT_DOUBLE_EQ(a->sim_time, 45.0);
  auto b = t.map(4, 700, 35.0);
  EXPECT_EQ(b->tick, 901u);
  EXPECT_DOUBLE_EQ(b->sim_time, 45.05);
}

TEST(InputHistory, ResendsFromASeqAndCountsWhatItNoLongerHolds) {
  InputHistory h;
  for (std::uint32_t s = 1; s <= 10; ++s) h.record({s, float(s), 0});
  std::vector<std::uint32_t> got;
  EXPECT_EQ(h.since(7, [&](const InputRecord& in) { got.push_back(in.seq); }), 0u);
  EXPECT_EQ(got, (std::vector<std::uint32_t>{7, 8, 9, 10}));
  EXPECT_EQ(h.newest(), 10u);

  InputHistory full;
  const std::uint32_t n = InputHistory::kCapacity + 20;
  for (std::uint32_t s = 1; s <= n; ++s) full.record({s, 0, 0});
  std::size_t count = 0;
  EXPECT_EQ(full.since(1, [&](const InputRecord&) { ++count; }), 20u) << "1..20 overwritten";
  EXPECT_EQ(count, InputHistory::kCapacity);
}

}  // namespace
}  // namespace zonesim::gateway
