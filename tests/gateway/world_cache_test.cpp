// World cache: ordering of samples from several zones and the handoff grace.
#include "gateway/world_cache.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "../gateway/gateway_fixture.h"
#include "gateway/client_view.h"

namespace zonesim::gateway {
namespace {

using testing::entity;

constexpr std::int64_t kGrace = 100'000'000;  // 100 ms
constexpr int kCell = 5;

// A keyframe of (cell, zone) at sim_time; it points into states, which must outlive it.
zonesim_dds_CellKeyframe keyframe(int cell, int zone, double sim_time,
                                  std::vector<zonesim_dds_EntityUpdate>& states) {
  zonesim_dds_CellKeyframe k{};
  k.cell = cell;
  k.zone = zone;
  k.tick = std::uint64_t(sim_time * 30);
  k.sim_time = sim_time;
  std::uint32_t n = std::uint32_t(states.size());
  k.entities = {n, n, states.data(), false};
  return k;
}

TEST(WorldCache, OlderSamplesAreIgnored) {
  WorldCache c(kGrace);
  EXPECT_TRUE(c.upsert(kCell, 0, 2.0, entity(1, 0, 10, 10)));
  EXPECT_FALSE(c.upsert(kCell, 0, 1.0, entity(1, 0, 99, 99)));
  EXPECT_EQ(c.find(1)->state.pos.x, 10);
  EXPECT_TRUE(c.upsert(kCell, 0, 3.0, entity(1, 0, 11, 10)));
  EXPECT_EQ(c.find(1)->state.pos.x, 11);
  EXPECT_EQ(c.stats().stale, 1u);
}

// A restored world (epoch 1, on the gateway's timeline: newer) replaces what was held and
// records how far each entity jumped; what it did not bring back is retired on request.
TEST(WorldCache, ARestoredEpochReplacesStatesRecordsJumpsAndRetiresTheRest) {
  WorldCache c(kGrace);
  EXPECT_TRUE(c.upsert(kCell, 0, 2.0, entity(1, 0, 10, 10), false, 60, 0));
  EXPECT_TRUE(c.upsert(kCell, 0, 2.0, entity(2, 0, 20, 10), false, 60, 0));
  // Entity 1 restored 3 m back along x; entity 2 absent from the restored world.
  EXPECT_TRUE(c.upsert(kCell, 0, 2.1, entity(1, 0, 7, 10), /*refresh_only=*/true, 61, 1));
  ASSERT_EQ(c.epochJumps().size(), 1u);
  EXPECT_NEAR(c.epochJumps()[0], 3.0, 1e-4);
  EXPECT_EQ(c.find(1)->epoch, 1u);
  EXPECT_EQ(c.retireEpochsBefore(1, 0), 1u);
  EXPECT_EQ(c.find(2), nullptr);
  EXPECT_NE(c.find(1), nullptr);
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

// Every kind a zone publishes enters, unique items (kind 4) too; a kind no zone has does not.
TEST(WorldCache, ItemsEnterAndUnknownKindsDoNot) {
  WorldCache c(kGrace);
  zonesim_dds_EntityUpdate item = entity(1, 0, 5, 5);
  item.kind = 4;
  EXPECT_TRUE(c.upsert(kCell, 0, 1.0, item));
  zonesim_dds_EntityUpdate unknown = entity(2, 0, 5, 5);
  unknown.kind = 5;
  EXPECT_FALSE(c.upsert(kCell, 0, 1.0, unknown));
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
  c.applyKeyframe(keyframe(kCell, 0, 2.0, kept), 0);
  c.sweep(kGrace);
  EXPECT_NE(c.find(1), nullptr);
  EXPECT_EQ(c.find(2), nullptr);
  EXPECT_NE(c.find(3), nullptr);
}

// Zones send a keyframe every K ticks for late joiners. For an entity already held from that
// (cell, zone) it is a refresh: the state is taken, the version kept, so clients following the
// entity are not resent it; they keep to the zone's own updates.
TEST(WorldCache, KeyframeRefreshesAHeldEntityWithoutANewVersion) {
  WorldCache c(kGrace);
  c.upsert(kCell, 0, 1.0, entity(1, 0, 10, 10, 1, 0));
  std::uint64_t v = c.find(1)->version;
  std::vector<zonesim_dds_EntityUpdate> states{entity(1, 0, 11, 10, 1, 0)};
  c.applyKeyframe(keyframe(kCell, 0, 2.0, states), 0);
  const CachedEntity* e = c.find(1);
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->version, v);
  EXPECT_EQ(e->state.pos.x, 11) << "the refresh still updates the state";
  EXPECT_EQ(e->sim_time, 2.0);
  // The zone's next update is a new version as before.
  EXPECT_TRUE(c.upsert(kCell, 0, 2.1, entity(1, 0, 11.1f, 10, 1, 0)));
  EXPECT_GT(c.find(1)->version, v);
}

TEST(WorldCache, KeyframeGivesEntitiesNewToTheCacheAVersion) {
  WorldCache c(kGrace);
  c.upsert(kCell, 0, 1.0, entity(1, 0, 10, 10));
  std::uint64_t v1 = c.find(1)->version;
  std::vector<zonesim_dds_EntityUpdate> states{entity(1, 0, 10, 10), entity(2, 0, 20, 10)};
  c.applyKeyframe(keyframe(kCell, 0, 2.0, states), 0);
  ASSERT_NE(c.find(2), nullptr);
  EXPECT_GT(c.find(2)->version, v1);
  EXPECT_EQ(c.find(1)->version, v1);
  // An entity removed (its leave's grace expired) and back in a later keyframe is new again.
  c.leave(kCell, 0, 2.1, 2, 0);
  ASSERT_EQ(c.sweep(kGrace), 1u);
  std::uint64_t newest = c.find(1)->version;
  std::vector<zonesim_dds_EntityUpdate> back{entity(1, 0, 10, 10), entity(2, 0, 21, 10)};
  c.applyKeyframe(keyframe(kCell, 0, 3.0, back), kGrace);
  ASSERT_NE(c.find(2), nullptr);
  EXPECT_GT(c.find(2)->version, newest);
  EXPECT_EQ(c.find(1)->version, v1);
}

TEST(WorldCache, KeyframeFromAnotherSourceGivesANewVersion) {
  WorldCache c(kGrace);
  c.upsert(kCell, 0, 1.0, entity(1, 0, 10, 10));
  std::uint64_t v = c.find(1)->version;
  // Same cell, another zone: the entity was handed over.
  std::vector<zonesim_dds_EntityUpdate> states{entity(1, 0, 10.5f, 10)};
  c.applyKeyframe(keyframe(kCell, 1, 2.0, states), 0);
  EXPECT_EQ(c.find(1)->zone, 1);
  EXPECT_GT(c.find(1)->version, v);
  v = c.find(1)->version;
  // Same zone, another cell: the entity crossed a cell border.
  states = {entity(1, 0, 26, 10)};
  c.applyKeyframe(keyframe(kCell + 1, 1, 3.0, states), 0);
  EXPECT_EQ(c.find(1)->cell, kCell + 1);
  EXPECT_GT(c.find(1)->version, v);
}

TEST(WorldCache, KeyframeOfAnEntityPendingRemovalGivesANewVersion) {
  WorldCache c(kGrace);
  c.upsert(kCell, 0, 1.0, entity(1, 0, 10, 10));
  ASSERT_TRUE(c.leave(kCell, 0, 1.1, 1, 0));
  std::uint64_t v = c.find(1)->version;
  std::vector<zonesim_dds_EntityUpdate> states{entity(1, 0, 12, 10)};
  c.applyKeyframe(keyframe(kCell, 0, 1.2, states), 0);
  EXPECT_GT(c.find(1)->version, v);
  EXPECT_EQ(c.find(1)->remove_at_ns, 0);
  EXPECT_EQ(c.sweep(kGrace * 5), 0u) << "the keyframe cancelled the leave";
}

TEST(WorldCache, OlderKeyframeNeitherRefreshesNorBumps) {
  WorldCache c(kGrace);
  c.upsert(kCell, 0, 2.0, entity(1, 0, 10, 10));
  std::uint64_t v = c.find(1)->version;
  std::vector<zonesim_dds_EntityUpdate> states{entity(1, 0, 99, 10)};
  c.applyKeyframe(keyframe(kCell, 0, 1.0, states), 0);
  EXPECT_EQ(c.find(1)->version, v);
  EXPECT_EQ(c.find(1)->state.pos.x, 10);
  EXPECT_EQ(c.stats().stale, 1u);
}

TEST(WorldCache, DroppedCellForgetsItsEntities) {
  WorldCache c(kGrace);
  c.upsert(kCell, 0, 1.0, entity(1, 0, 1, 1));
  c.upsert(kCell + 1, 0, 1.0, entity(2, 0, 30, 1));
  c.dropCell(kCell);
  EXPECT_EQ(c.find(1), nullptr);
  EXPECT_NE(c.find(2), nullptr);
}

TEST(WorldCache, PredictsWithTheEntitysOwnModel) {
  WorldCache c(kGrace);
  c.upsert(kCell, 0, 1.0, entity(1, 0, 10, 20, 2, -1), false, 30);
  dr::V3 p = predictedPosition(*c.find(1), 1.5);
  EXPECT_FLOAT_EQ(float(p.x), 11);
  EXPECT_FLOAT_EQ(float(p.z), 19.5f);
  EXPECT_EQ(wireEntity(*c.find(1)).tick, 30u);
  zonesim_dds_EntityUpdate still = entity(2, 3, 10, 20, 2, -1);
  still.model = 0;  // static: the velocity is not extrapolated
  c.upsert(kCell, 0, 1.0, still);
  EXPECT_FLOAT_EQ(float(predictedPosition(*c.find(2), 1.5).x), 10);
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

// The client-facing consequence: a periodic keyframe sends nothing to clients that already see
// its entities, while a client that starts seeing one gets the refreshed state in its Spawn.
TEST(WorldCache, PeriodicKeyframeResendsNothingToFollowingClients) {
  WorldCache c(kGrace);
  InterestGrid grid(SceneBox{{0, 0, 0}, {100, 10, 100}}, 25);
  ViewPoint at;
  at.x = 50, at.z = 10, at.nimbus = 40, at.keep = 44, at.sim_now = 2.0;
  int cell = grid.cellOf(50, 10);
  c.upsert(cell, 0, 1.0, entity(7, 0, 50, 10));
  c.upsert(cell, 0, 1.0, entity(8, 0, 55, 10));
  ClientView following;
  EXPECT_EQ(following.diff(selectVisible(c, grid, at, following)).spawns.size(), 2u);

  std::vector<zonesim_dds_EntityUpdate> states{entity(7, 0, 51, 10), entity(8, 0, 55, 10)};
  c.applyKeyframe(keyframe(cell, 0, 2.0, states), 0);
  EXPECT_TRUE(following.diff(selectVisible(c, grid, at, following)).empty());

  ClientView late;
  EXPECT_EQ(late.diff(selectVisible(c, grid, at, late)).spawns, (std::vector<std::uint64_t>{7, 8}));
  EXPECT_FLOAT_EQ(float(predictedPosition(*c.find(7), at.sim_now).x), 51);

  c.upsert(cell, 0, 2.1, entity(7, 0, 51.2f, 10));
  EXPECT_EQ(following.diff(selectVisible(c, grid, at, following)).updates,
            std::vector<std::uint64_t>{7});
}

}  // namespace
}  // namespace zonesim::gateway
