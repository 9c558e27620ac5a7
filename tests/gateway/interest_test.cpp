// Interest: the per-player diff and the shared, refcounted cell set.
#include <gtest/gtest.h>

#include "../gateway/gateway_fixture.h"
#include "gateway/client_view.h"
#include "gateway/interest_manager.h"
#include "gateway/world_cache.h"
#include "gateway/world_snapshot.h"

namespace zonesim::gateway {
namespace {

using testing::entity;
using Ids = std::vector<std::uint64_t>;

TEST(ClientView, SpawnsDespawnsAndUpdates) {
  ClientView v;
  ViewDiff d = v.diff({{3, 1}, {1, 1}, {2, 1}});
  EXPECT_EQ(d.spawns, (Ids{1, 2, 3}));
  EXPECT_TRUE(d.updates.empty());
  EXPECT_TRUE(d.despawns.empty());
  d = v.diff({{1, 1}, {2, 5}, {4, 1}});
  EXPECT_EQ(d.spawns, (Ids{4}));
  EXPECT_EQ(d.updates, (Ids{2}));
  EXPECT_EQ(d.despawns, (Ids{3}));
  d = v.diff({{1, 1}, {2, 5}, {4, 1}});
  EXPECT_TRUE(d.empty()) << "nothing fresh, nothing to send";
  EXPECT_EQ(v.size(), 3u);
}

TEST(ClientView, AHeldDespawnIsListedAgainOrBecomesAnUpdateIfTheEntityCameBack) {
  ClientView v;
  v.diff({{1, 1}, {2, 1}});
  ViewDiff d = v.diff({});
  EXPECT_EQ(d.despawns, (Ids{1, 2}));
  v.holdDespawn(1);  // no room this tick: the client still holds 1
  v.holdDespawn(2);
  EXPECT_EQ(v.size(), 2u);
  d = v.diff({{2, 1}});
  EXPECT_EQ(d.despawns, (Ids{1})) << "still gone: listed again";
  EXPECT_EQ(d.updates, (Ids{2})) << "back in view: the client holds it, so it gets the state";
  EXPECT_TRUE(d.spawns.empty());
  d = v.diff({{2, 1}});
  EXPECT_TRUE(d.empty());
}

TEST(SelectVisible, NimbusWithHysteresisAndTheAvatarAlways) {
  WorldCache c(1);
  InterestGrid grid(SceneBox{{0, 0, 0}, {200, 10, 200}}, 25);
  auto put = [&](std::uint64_t id, float x, float z) {
    c.upsert(grid.cellOf(x, z), 0, 1.0, entity(id, 0, x, z));
  };
  put(1, 100, 100);  // the avatar
  put(2, 130, 100);  // 30 m: inside
  put(3, 142, 100);  // 42 m: between nimbus and keep
  put(4, 190, 100);  // 90 m: outside
  ViewPoint at;
  at.x = 100, at.z = 100, at.nimbus = 40, at.keep = 44, at.self = 1, at.sim_now = 1.0;
  ClientView view;
  Ids seen;
  for (auto& e : selectVisible(c, grid, at, view)) seen.push_back(e.id);
  std::sort(seen.begin(), seen.end());
  EXPECT_EQ(seen, (Ids{1, 2}));
  // Once known, entity 3 would stay until beyond `keep`.
  view.diff({{1, 1}, {2, 1}, {3, 1}});
  seen.clear();
  for (auto& e : selectVisible(c, grid, at, view)) seen.push_back(e.id);
  std::sort(seen.begin(), seen.end());
  EXPECT_EQ(seen, (Ids{1, 2, 3}));
}

TEST(WorldSnapshot, GroupsByCellAndPredictsToItsTime) {
  WorldCache c(1);
  InterestGrid grid(SceneBox{{0, 0, 0}, {200, 10, 200}}, 50);
  // Moving 2 m/s along x, sampled at t = 1: at t = 2 it is 2 m on.
  c.upsert(grid.cellOf(10, 10), 0, 1.0, entity(1, 0, 10, 10, 2, 0));
  c.upsert(grid.cellOf(120, 10), 0, 1.0, entity(2, 0, 120, 10));
  c.upsert(grid.cellOf(130, 20), 0, 1.0, entity(3, 2, 130, 20));
  WorldSnapshot snap;
  snap.rebuild(c, grid, 2.0);
  EXPECT_EQ(snap.size(), 3u);
  ASSERT_EQ(snap.cell(grid.cellOf(10, 10)).size(), 1u);
  EXPECT_NEAR(snap.cell(grid.cellOf(10, 10))[0].x, 12.0, 1e-3);
  EXPECT_EQ(snap.cell(grid.cellOf(120, 10)).size(), 2u);
  EXPECT_TRUE(snap.cell(grid.cellOf(190, 190)).empty());
  EXPECT_TRUE(snap.cell(-1).empty());
  EXPECT_TRUE(snap.cell(grid.cellCount()).empty());
  // Filed where it is predicted to be, not where its zone sampled it: 45 m at 10 m/s is 55 m.
  c.upsert(grid.cellOf(45, 80), 0, 1.0, entity(4, 0, 45, 80, 10, 0));
  snap.rebuild(c, grid, 2.0);
  EXPECT_TRUE(snap.cell(grid.cellOf(45, 80)).empty());
  ASSERT_EQ(snap.cell(grid.cellOf(55, 80)).size(), 1u);
  EXPECT_EQ(snap.cell(grid.cellOf(55, 80))[0].id, 4u);
  c.dropCell(grid.cellOf(45, 80));
  // Rebuilt after a removal, nothing stale stays.
  c.dropCell(grid.cellOf(120, 10));
  snap.rebuild(c, grid, 2.0);
  EXPECT_EQ(snap.size(), 1u);
  EXPECT_TRUE(snap.cell(grid.cellOf(120, 10)).empty());
}

TEST(WorldSnapshot, ListsPerCellWhatChangedSinceTheRebuildBefore) {
  WorldCache c(1);
  InterestGrid grid(SceneBox{{0, 0, 0}, {200, 10, 200}}, 50);
  for (std::uint64_t id = 1; id <= 4; ++id)
    c.upsert(grid.cellOf(10, 10), 0, 1.0, entity(id, 0, 10, float(id)));
  WorldSnapshot snap;
  snap.rebuild(c, grid, 1.0);
  EXPECT_EQ(snap.changedIn(grid.cellOf(10, 10)).size(), 4u) << "the first rebuild: all new";
  snap.rebuild(c, grid, 1.1);
  EXPECT_TRUE(snap.changedIn(grid.cellOf(10, 10)).empty()) << "nothing arrived in between";
  c.upsert(grid.cellOf(10, 10), 0, 1.2, entity(3, 0, 10, 3.5f));
  c.upsert(grid.cellOf(120, 10), 0, 1.2, entity(9, 0, 120, 10));
  snap.rebuild(c, grid, 1.2);
  ASSERT_EQ(snap.changedIn(grid.cellOf(10, 10)).size(), 1u);
  EXPECT_EQ(snap.changedIn(grid.cellOf(10, 10))[0].id, 3u);
  ASSERT_EQ(snap.changedIn(grid.cellOf(120, 10)).size(), 1u);
  EXPECT_EQ(snap.changedIn(grid.cellOf(120, 10))[0].id, 9u);
  EXPECT_EQ(snap.cell(grid.cellOf(10, 10)).size(), 4u) << "the full list is unchanged";
  EXPECT_TRUE(snap.changedIn(-1).empty());
}

TEST(SelectChanged, BetweenFullScansOnlyHeldEntitiesThatChangedAreUpdated) {
  WorldCache c(1);
  InterestGrid grid(SceneBox{{0, 0, 0}, {400, 10, 400}}, 25);
  for (std::uint64_t id = 1; id <= 6; ++id)
    c.upsert(grid.cellOf(100, 100), 0, 1.0, entity(id, 0, 100 + float(id), 100));
  c.upsert(grid.cellOf(300, 300), 0, 1.0, entity(7, 0, 300, 300));  // far away
  ViewPoint at;
  at.x = 100, at.z = 100, at.nimbus = 60, at.keep = 66, at.sim_now = 1.0;
  WorldSnapshot snap;
  snap.rebuild(c, grid, at.sim_now);
  ClientView view;
  std::vector<VisibleEntity> visible;
  selectVisible(snap, grid, at, view, visible);
  ViewDiff d;
  view.diff(visible, d);
  EXPECT_EQ(d.spawns, (Ids{1, 2, 3, 4, 5, 6}));
  view.forget(6);  // as a budget does with a spawn it held back: the client lacks 6
  // New states of 2, of 6 (not held) and of the far 7; and a new entity 8 nearby.
  for (std::uint64_t id : {2u, 6u})
    c.upsert(grid.cellOf(100, 100), 0, 1.1, entity(id, 0, 100 + float(id), 101));
  c.upsert(grid.cellOf(300, 300), 0, 1.1, entity(7, 0, 300, 301));
  c.upsert(grid.cellOf(100, 100), 0, 1.1, entity(8, 0, 108, 100));
  snap.rebuild(c, grid, 1.1);
  selectChanged(snap, grid, at, view, visible);
  view.diffKnown(visible, d);
  EXPECT_EQ(d.updates, (Ids{2})) << "only what the client holds; spawns wait for a full scan";
  EXPECT_TRUE(d.spawns.empty());
  EXPECT_TRUE(d.despawns.empty());
  view.diffKnown(visible, d);
  EXPECT_TRUE(d.empty()) << "a version is sent once";
  // The next full scan catches up on the rest.
  selectVisible(snap, grid, at, view, visible);
  view.diff(visible, d);
  EXPECT_EQ(d.spawns, (Ids{6, 8}));
  EXPECT_TRUE(d.updates.empty());
}

TEST(SelectVisible, ASnapshotGivesTheRuleAtPredictedPositionsAndReusesItsOutput) {
  WorldCache c(1);
  InterestGrid grid(SceneBox{{0, 0, 0}, {400, 10, 400}}, 25);
  for (std::uint64_t id = 1; id <= 400; ++id) {
    float x = float((id * 37) % 400), z = float((id * 91) % 400);
    c.upsert(grid.cellOf(x, z), 0, 1.0, entity(id, std::uint8_t(id % 3), x, z, 1, -1));
  }
  ViewPoint at;
  at.x = 200, at.z = 180, at.nimbus = 60, at.keep = 66, at.self = 5, at.sim_now = 1.5;
  at.aura = {80, 40, 100, 100};
  ClientView view;
  view.diff(selectVisible(c, grid, at, view));  // known: keep applies
  WorldSnapshot snap;
  snap.rebuild(c, grid, at.sim_now);
  std::vector<VisibleEntity> out{{999, 9}};  // stale content is cleared
  at.self_version = c.find(5)->version;
  selectVisible(snap, grid, at, view, out);
  auto ids = [](const std::vector<VisibleEntity>& v) {
    Ids r;
    for (auto& e : v) r.push_back(e.id);
    std::sort(r.begin(), r.end());
    return r;
  };
  // Against every entity tested by hand: the rule, at the predicted positions.
  Ids expected;
  for (std::uint64_t id = 1; id <= 400; ++id) {
    const CachedEntity& e = *c.find(id);
    dr::V3 p = predictedPosition(e, at.sim_now);
    double d2 = (p.x - at.x) * (p.x - at.x) + (p.z - at.z) * (p.z - at.z);
    double aura = at.aura[e.state.kind];
    if (id == at.self || auraNimbusAllows(d2, aura, at.nimbus) ||
        (view.knows(id) && auraNimbusAllows(d2, aura * 1.1, at.keep)))
      expected.push_back(id);
  }
  EXPECT_EQ(ids(out), expected);
  EXPECT_EQ(ids(selectVisible(c, grid, at, view)), expected);
  EXPECT_GT(expected.size(), 20u);
  EXPECT_LT(expected.size(), 200u);
  EXPECT_TRUE(std::binary_search(expected.begin(), expected.end(), 5u)) << "the avatar, always";
}

TEST(AuraNimbus, BothRangesMustHold) {
  // A sees B when A is inside B's aura and B inside A's nimbus.
  // Distances are given squared.
  EXPECT_TRUE(auraNimbusAllows(50 * 50, 80, 60));
  EXPECT_FALSE(auraNimbusAllows(70 * 70, 80, 60)) << "outside A's nimbus";
  EXPECT_FALSE(auraNimbusAllows(50 * 50, 40, 60)) << "A outside B's aura";
  EXPECT_TRUE(auraNimbusAllows(60 * 60, 60, 60));
  // The nimbus grows with speed, within its cap, never shrinking below the base.
  EXPECT_DOUBLE_EQ(grownNimbus(60, 0, 4, 150), 60);
  EXPECT_DOUBLE_EQ(grownNimbus(60, 5, 4, 150), 80);
  EXPECT_DOUBLE_EQ(grownNimbus(60, 50, 4, 150), 150);
  EXPECT_DOUBLE_EQ(grownNimbus(60, 50, 4, 30), 60);
}

TEST(SelectVisible, AurasPerKindAndASpeedGrownNimbus) {
  WorldCache c(1);
  InterestGrid grid(SceneBox{{0, 0, 0}, {400, 10, 400}}, 25);
  auto put = [&](std::uint64_t id, std::uint8_t kind, float x) {
    c.upsert(grid.cellOf(x, 100), 0, 1.0, entity(id, kind, x, 100));
  };
  put(1, 1, 100);  // the avatar
  put(2, 0, 150);  // NPC at 50 m; NPC aura 60
  put(3, 0, 170);  // NPC at 70 m: outside the NPC aura whatever the nimbus
  put(4, 3, 170);  // emitter at 70 m; emitter aura 200
  put(5, 3, 250);  // emitter at 150 m
  ViewPoint at;
  at.x = 100, at.z = 100, at.self = 1, at.sim_now = 1.0;
  at.aura = {60, 150, 60, 200};
  auto seen = [&](double nimbus) {
    at.nimbus = nimbus;
    at.keep = nimbus * 1.1;
    Ids ids;
    for (auto& e : selectVisible(c, grid, at, ClientView())) ids.push_back(e.id);
    std::sort(ids.begin(), ids.end());
    return ids;
  };
  // A walker (nimbus 60) sees the near NPC only; running at 10 m/s (nimbus 60 + 10 * 4 =
  // 100) it also sees the emitter at 70 m, and a flyer's 160 m nimbus reaches the far
  // emitter; the NPC at 70 m stays beyond its own aura for all of them.
  EXPECT_EQ(seen(grownNimbus(60, 0, 4, 160)), (Ids{1, 2}));
  EXPECT_EQ(seen(grownNimbus(60, 10, 4, 160)), (Ids{1, 2, 4}));
  EXPECT_EQ(seen(grownNimbus(60, 40, 4, 160)), (Ids{1, 2, 4, 5}));
}

TEST(InterestManager, APlayersOwnRadiusWidensItsCells) {
  InterestGrid grid(SceneBox{{0, 0, 0}, {400, 10, 400}}, 50);
  InterestManager m(grid, 40, 10);
  CellDelta d;
  m.update(1, 200, 200, d);
  std::size_t walker = m.cellsOf(1).size();
  m.update(2, 200, 200, d, 140);
  EXPECT_GT(m.cellsOf(2).size(), walker);
  // The wider set contains the narrower one: one shared reader per cell.
  for (int cell : m.cellsOf(1)) EXPECT_EQ(m.refcount(cell), 2);
}

TEST(InterestManager, SharedCellsAreRefcounted) {
  InterestGrid grid(SceneBox{{0, 0, 0}, {200, 10, 200}}, 25);
  InterestManager m(grid, 20, 5);
  CellDelta d;
  m.update(1, 50, 50, d);
  std::vector<int> first = d.added;
  EXPECT_FALSE(first.empty());
  EXPECT_EQ(m.subscribedCells(), first.size());
  CellDelta d2;
  m.update(2, 50, 50, d2);
  EXPECT_TRUE(d2.empty()) << "the second player reuses the same readers";
  for (int c : first) EXPECT_EQ(m.refcount(c), 2);
  CellDelta d3;
  m.remove(1, d3);
  EXPECT_TRUE(d3.empty());
  m.remove(2, d3);
  EXPECT_EQ(d3.removed.size(), first.size());
  EXPECT_EQ(m.subscribedCells(), 0u);
}

TEST(InterestManager, MovingSwapsCellsWithHysteresis) {
  InterestGrid grid(SceneBox{{0, 0, 0}, {200, 10, 200}}, 25);
  InterestManager m(grid, 10, 5);
  CellDelta d;
  m.update(1, 37.5, 37.5, d);  // the centre of cell (1, 1): only that cell
  EXPECT_EQ(d.added, std::vector<int>{grid.cellOf(37.5, 37.5)});
  d = {};
  m.update(1, 56, 37.5, d);  // 6 m into cell (2, 1); cell (1, 1) is 6 m away: still held
  EXPECT_EQ(d.added, std::vector<int>{grid.cellOf(56, 37.5)});
  EXPECT_TRUE(d.removed.empty());
  d = {};
  m.update(1, 66, 37.5, d);  // now 16 m from cell (1, 1): beyond radius + hysteresis
  EXPECT_EQ(d.removed, std::vector<int>{grid.cellOf(37.5, 37.5)});
}

}  // namespace
}  // namespace zonesim::gateway
