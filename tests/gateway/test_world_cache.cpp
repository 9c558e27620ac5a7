// World cache: ordering of samples from several zones and the handoff grace.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "../gateway/test_support.h"
#include "gateway/client_view.h"
#include "gateway/world_cache.h"

namespace zonesim::gateway {
namespace {

using testing::entity;

constexpr std::int64_t kGrace = 100'000'000;  // 100 ms
constexpr int kCell = 5;

TEST(WorldCache, OlderSamplesAreIgnored) {
  WorldCache c(kGrace);
  EXPECT_TRUE(c.upsert(kCell, 0, 2.0, entity(1, 0, 10, 10)));
  EXPECT_FALSE(c.upsert(kCell, 0, 1.0, entity(1, 0, 99, 99)));
  EXPECT_EQ(c.find(1)->state.pos.x, 10);
  EXPECT_TRUE(c.upsert(kCell, 0, 3.0, entity(1, 0, 11, 10)));
  EXPECT_EQ(c.find(1)->state.pos.x, 11);
  EXPECT_EQ(c.stats().stale, 1u);
}

TEST(WorldCache, VersionsGrowWithEveryAcceptedSample) {
  WorldCache c(kGrace);
  c.upsert(kCell, 0, 1.0, entity(1, 0, 1, 1));
  std::uint64_t v1 = c.find(1)->version;
  c.upsert(kCell, 0, 1.5, entity(1, 0, 2, 1));
  EXPECT_GT(c.find(1)->version, v1);
}

TEST(WorldCache, NonFiniteStatesNeverEnter) {
  WorldCache c(kGrace);
  EXPECT_FALSE(c.upsert(kCell, 0, 1.0, entity(1, 0, std::nanf(""), 0)));
  EXPECT_EQ(c.find(1), nullptr);
  EXPECT_EQ(c.stats().invalid, 1u);
}

// Handoff: zone A says "left (migrated)", zone B says "entered", same tick, either order.
TEST(WorldCache, HandoffLeaveThenEnterNeverRemoves) {
  WorldCache c(kGrace);
  c.upsert(kCell, 0, 1.0, entity(1, 1, 49, 10));
  EXPECT_TRUE(c.leave(kCell, 0, 1.1, 1, 0));
  EXPECT_TRUE(c.upsert(kCell, 1, 1.1, entity(1, 1, 50.1f, 10)));
  EXPECT_EQ(c.sweep(kGrace * 5), 0u);
  ASSERT_NE(c.find(1), nullptr);
  EXPECT_EQ(c.find(1)->zone, 1);
}

TEST(WorldCache, HandoffEnterThenLeaveNeverRemoves) {
  WorldCache c(kGrace);
  c.upsert(kCell, 0, 1.0, entity(1, 1, 49, 10));
  EXPECT_TRUE(c.upsert(kCell, 1, 1.1, entity(1, 1, 50.1f, 10)));
  EXPECT_FALSE(c.leave(kCell, 0, 1.1, 1, 0)) << "the leave is for a source no longer current";
  EXPECT_EQ(c.sweep(kGrace * 5), 0u);
  ASSERT_NE(c.find(1), nullptr);
}

TEST(WorldCache, LeaveWithoutEnterRemovesAfterTheGrace) {
  WorldCache c(kGrace);
  c.upsert(kCell, 0, 1.0, entity(1, 0, 10, 10));
  c.leave(kCell, 0, 1.1, 1, 1000);
  EXPECT_EQ(c.sweep(1000 + kGrace - 1), 0u);
  EXPECT_NE(c.find(1), nullptr) << "still inside the grace";
  EXPECT_EQ(c.sweep(1000 + kGrace), 1u);
  EXPECT_EQ(c.find(1), nullptr);
  // A late sample older than the leave does not resurrect it...
  EXPECT_FALSE(c.upsert(kCell, 0, 1.05, entity(1, 0, 10, 10)));
  // ...but the entity coming back later does.
  EXPECT_TRUE(c.upsert(kCell, 0, 2.0, entity(1, 0, 10, 10)));
}

TEST(WorldCache, KeyframeRemovesWhatIsNoLongerThere) {
  WorldCache c(kGrace);
  c.upsert(kCell, 0, 1.0, entity(1, 0, 1, 1));
  c.upsert(kCell, 0, 1.0, entity(2, 0, 2, 2));
  c.upsert(kCell, 1, 1.0, entity(3, 0, 3, 3));  // same cell, other zone: not its business
  std::vector<zonesim_dds_EntityUpdate> kept{entity(1, 0, 1.5f, 1)};
  zonesim_dds_CellKeyframe k{};
  k.cell = kCell;
  k.zone = 0;
  k.tick = 60;
  k.sim_time = 2.0;
  k.entities = {1, 1, kept.data(), false};
  c.applyKeyframe(k, 0);
  c.sweep(kGrace);
  EXPECT_NE(c.find(1), nullptr);
  EXPECT_EQ(c.find(2), nullptr);
  EXPECT_NE(c.find(3), nullptr);
}

TEST(WorldCache, DroppedCellForgetsItsEntities) {
  WorldCache c(kGrace);
  c.upsert(kCell, 0, 1.0, entity(1, 0, 1, 1));
  c.upsert(kCell + 1, 0, 1.0, entity(2, 0, 30, 1));
  c.dropCell(kCell);
  EXPECT_EQ(c.find(1), nullptr);
  EXPECT_NE(c.find(2), nullptr);
}

TEST(WorldCache, ExtrapolatesFirstOrder) {
  WorldCache c(kGrace);
  c.upsert(kCell, 0, 1.0, entity(1, 0, 10, 20, 2, -1));
  proto::EntityState s = extrapolatedState(*c.find(1), 1.5);
  EXPECT_FLOAT_EQ(s.pos().x(), 11);
  EXPECT_FLOAT_EQ(s.pos().z(), 19.5f);
}

// The client-facing consequence: the handoff produces an update, never a despawn + spawn.
TEST(WorldCache, HandoffShowsTheClientNoDespawn) {
  WorldCache c(kGrace);
  InterestGrid grid(SceneBox{{0, 0, 0}, {100, 10, 100}}, 25);
  ClientView view;
  ViewPoint at;
  at.x = 50, at.z = 10, at.nimbus = 40, at.keep = 44;
  int cell = grid.cellOf(49, 10);
  c.upsert(cell, 0, 1.0, entity(7, 0, 49, 10));
  EXPECT_EQ(view.diff(selectVisible(c, grid, at, view)).spawns.size(), 1u);
  c.leave(cell, 0, 1.1, 7, 0);
  ViewDiff during = view.diff(selectVisible(c, grid, at, view));
  EXPECT_TRUE(during.despawns.empty());
  c.upsert(cell, 1, 1.1, entity(7, 0, 50, 10));
  c.sweep(kGrace * 2);
  ViewDiff after = view.diff(selectVisible(c, grid, at, view));
  EXPECT_TRUE(after.despawns.empty());
  EXPECT_TRUE(after.spawns.empty());
  EXPECT_EQ(after.updates, std::vector<std::uint64_t>{7});
}

}  // namespace
}  // namespace zonesim::gateway
