// Sessions: ids, tokens, lookups and generation-checked slot reuse.
#include "gateway/session_table.h"

#include <gtest/gtest.h>

#include <set>

namespace zonesim::gateway {
namespace {

const Endpoint kA = Endpoint::loopback(40001), kB = Endpoint::loopback(40002);

TEST(SessionTable, PlayerIdsCarryTheGatewayId) {
  SessionTable t(3, 16);
  auto h1 = t.create(kA, 1, 0), h2 = t.create(kB, 2, 0);
  ASSERT_TRUE(h1 && h2);
  EXPECT_EQ(t.get(*h1)->player_id, (std::uint64_t{3} << 32) | 1);
  EXPECT_EQ(t.get(*h2)->player_id, (std::uint64_t{3} << 32) | 2);
}

TEST(SessionTable, ARestartedGatewayIssuesIdsTheZonesHaveNotSeen) {
  // Same --gateway-id, two processes (two incarnations): the first players differ.
  SessionTable before(3, 16, 0x1234), after(3, 16, 0x4321);
  auto a = before.create(kA, 1, 0), b = after.create(kA, 1, 0);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(before.get(*a)->player_id,
            (std::uint64_t{0x1234} << 48) | (std::uint64_t{3} << 32) | 1);
  EXPECT_NE(before.get(*a)->player_id, after.get(*b)->player_id);
}

TEST(SessionTable, TokensAreNonZeroAndDistinct) {
  SessionTable t(1, 1000);
  std::set<std::uint64_t> tokens;
  for (std::uint64_t i = 1; i <= 1000; ++i) {
    auto h = t.create(Endpoint::loopback(std::uint16_t(1000 + i)), i, 0);
    ASSERT_TRUE(h);
    EXPECT_NE(t.get(*h)->token, 0u);
    tokens.insert(t.get(*h)->token);
  }
  EXPECT_EQ(tokens.size(), 1000u);
  EXPECT_FALSE(t.create(kA, 5000, 0)) << "limit reached";
}

TEST(SessionTable, LookupsFindTheSameSession) {
  SessionTable t(1, 16);
  auto h = *t.create(kA, 77, 5);
  const Session& s = *t.get(h);
  EXPECT_EQ(t.findByToken(s.token), h);
  EXPECT_EQ(t.findByPlayer(s.player_id), h);
  EXPECT_EQ(t.findByHello(kA, 77), h);
  EXPECT_FALSE(t.findByHello(kB, 77));
  EXPECT_FALSE(t.findByHello(kA, 78));
}

TEST(SessionTable, ReusedSlotInvalidatesOldHandles) {
  SessionTable t(1, 16);
  SlotHandle old = *t.create(kA, 1, 0);
  std::uint64_t old_token = t.get(old)->token;
  ASSERT_TRUE(t.erase(old));
  EXPECT_EQ(t.get(old), nullptr);
  EXPECT_FALSE(t.findByToken(old_token));
  SlotHandle fresh = *t.create(kB, 2, 0);
  EXPECT_EQ(fresh.index, old.index) << "the slot is reused";
  EXPECT_NE(fresh.generation, old.generation);
  EXPECT_EQ(t.get(old), nullptr) << "a stale handle must not reach the new player";
  EXPECT_NE(t.get(fresh), nullptr);
  EXPECT_FALSE(t.erase(old));
  EXPECT_EQ(t.size(), 1u);
}

}  // namespace
}  // namespace zonesim::gateway
