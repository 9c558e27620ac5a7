// Ant colonies in a zone (zone_node/systems/ant_movement.h) on the courtyard map: the ants find
// the food behind the walls and the colony's trail route ends within a stated factor of the A*
// optimum; once the food is gone the trail fades exactly as (1 - rho)^t; ant choices do not
// depend on the other ants a rank holds; a nest on a wall is a scene error.

#include "zone_node/systems/ant_movement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "ai/grid_path.h"
#include "ai/grid_search.h"
#include "common/scene.h"
#include "zone_node/population.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/world_map.h"

namespace zonesim::zone {
namespace {

std::string source(const std::string& relative) {
  return std::string(ZONESIM_SOURCE_DIR) + "/" + relative;
}

struct Colony {
  explicit Colony(const Scene& s) : scene(s), map(loadWorldMap(s)), ants(s, map.get()) {
    forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  }
  void run(int ticks) {
    LoneZone lone{scene.dt};  // one rank: its deltas are the sum
    lone.players = players;
    for (int k = 0; k < ticks; ++k, ++tick) {
      lone.step(ants, store, tick);
      updates += ants.updates();
    }
  }
  const Scene& scene;
  std::shared_ptr<const WorldMap> map;
  AntMovement ants;
  EntityStore store;
  std::uint64_t tick = 0;
  std::vector<crowd::Vec2> players;  // for level of detail
  std::size_t updates = 0;           // ant walks taken
};

double optimum(const Scene& scene, const WorldMap& map) {
  const NpcColony& c = scene.npcs[0].colony;
  ai::GridSearch search(map.grid);
  ai::GridPath path;
  EXPECT_TRUE(search.findPath(map.frame.cellOf({c.nest.x, c.nest.z}),
                              map.frame.cellOf({c.food.x, c.food.z}), path));
  return path.length;
}

TEST(AntMovement, TheColonysTrailConvergesNearTheAStarRoute) {
  Scene scene = loadScene(source("scenes/courtyard_ants.yaml"));
  Colony c(scene);
  const double best = optimum(scene, *c.map);
  c.run(int(180 / scene.dt));
  const ColonyStats before = c.ants.stats(0);
  c.run(int(60 / scene.dt));  // the fourth minute: the routes the colony walks now
  const ColonyStats& s = c.ants.stats(0);
  const double recent = (s.length_sum - before.length_sum) / double(s.trips - before.trips);
  std::vector<ai::Cell> route = c.ants.trailRoute(0);
  ASSERT_FALSE(route.empty());
  const double trail = ai::pathLength(route);
  std::printf(
      "%llu trips (%llu in the fourth minute, mean route %.1f m; first three minutes "
      "%.1f m); trail route %.1f m; A* %.1f m (%.3fx, %.3fx)\n",
      (unsigned long long)s.trips, (unsigned long long)(s.trips - before.trips), recent,
      before.length_sum / double(before.trips), trail, best, recent / best, trail / best);
  EXPECT_GT(s.trips - before.trips, 40u);
  EXPECT_LT(recent, 1.3 * best);  // the stated factors (measured 1.20x and 1.20x)
  EXPECT_LT(trail, 1.25 * best);
  int on_walls = 0;
  for (std::size_t i = 0; i < c.store.size(); ++i)
    on_walls += c.map->walkable(c.store.pos[i].x(), c.store.pos[i].z()) ? 0 : 1;
  EXPECT_EQ(on_walls, 0);
}

TEST(AntMovement, AnAbandonedTrailFadesAsOneMinusRhoToTheT) {
  Scene scene = loadScene(source("scenes/courtyard_ants.yaml"));
  NpcColony& col = scene.npcs[0].colony;
  col.food_until = 120;
  Colony c(scene);
  c.run(int(120 / scene.dt));
  // Wait until every ant that found food before it went has laid its trail home.
  auto layers = [&] {
    int n = 0;
    for (std::size_t i = 0; i < c.store.size(); ++i)
      n += std::get<AntData>(c.store.npc[i].crowd).mode == int(AntMode::Returning) &&
           std::get<AntData>(c.store.npc[i].crowd).route_length > 0;
    return n;
  };
  while (layers() > 0 && c.tick < std::uint64_t(400 / scene.dt)) c.run(1);
  ASSERT_EQ(layers(), 0);
  // The strongest cell next to the food, now and 30 s later.
  ai::Cell food = c.map->frame.cellOf({col.food.x, col.food.z});
  const double before = c.ants.trail(0, food), total_before = c.ants.totalTrail(0);
  const int ticks = int(std::lround(30 / scene.dt));
  c.run(ticks);
  const double after = c.ants.trail(0, food);
  const double expected = before * std::pow(1 - col.evaporation, ticks * scene.dt);
  std::printf(
      "food cell trail %.5f -> %.5f after 30 s (analytic %.5f, rel. error %.2e); total "
      "%.3f -> %.3f\n",
      before, after, expected, std::abs(after - expected) / expected, total_before,
      c.ants.totalTrail(0));
  EXPECT_GT(before, 10 * col.initial_pheromone);  // it was a trail
  // Integer evaporation rounds down by under one unit (1 / kTrailScale) per tick.
  EXPECT_NEAR(after, expected, ticks / kTrailScale);
  EXPECT_LT(c.ants.totalTrail(0), 0.6 * total_before);
}

TEST(AntMovement, AnAntsWalkDoesNotDependOnTheOtherAntsItIsSteppedWith) {
  // Two "ranks" holding halves of the colony, trails summed, against one holding all of it.
  Scene scene = loadScene(source("scenes/courtyard_ants.yaml"));
  Colony whole(scene), a(scene), b(scene);
  EntityStore& sa = a.store;
  EntityStore& sb = b.store;
  for (std::size_t i = sa.size(); i-- > 0;)
    if (i % 2) sa.removeAt(i);
  for (std::size_t i = sb.size(); i-- > 0;)
    if (i % 2 == 0) sb.removeAt(i);
  for (std::uint64_t t = 0; t < 1200; ++t) {
    whole.ants.walk(whole.store, t, scene.dt);
    whole.ants.applyTrails();
    a.ants.walk(sa, t, scene.dt);
    b.ants.walk(sb, t, scene.dt);
    std::span<std::int64_t> da = a.ants.deltas(), db = b.ants.deltas();
    for (std::size_t k = 0; k < da.size(); ++k) da[k] = db[k] = da[k] + db[k];
    a.ants.applyTrails();
    b.ants.applyTrails();
  }
  int compared = 0;
  for (const EntityStore* part : {&sa, &sb}) {
    for (std::size_t i = 0; i < part->size(); ++i) {
      std::size_t w = *whole.store.indexOf(part->id[i]);
      EXPECT_EQ(part->pos[i].x(), whole.store.pos[w].x());
      EXPECT_EQ(part->pos[i].z(), whole.store.pos[w].z());
      EXPECT_EQ(std::get<AntData>(part->npc[i].crowd).route,
                std::get<AntData>(whole.store.npc[w].crowd).route);
      ++compared;
    }
  }
  EXPECT_EQ(compared, 40);
  EXPECT_EQ(a.ants.totalTrail(0), whole.ants.totalTrail(0));
  EXPECT_GT(whole.ants.stats(0).trips, 0u);
}

TEST(AntMovement, UnderLodFarAntsWalkLessOftenAndTheColonyStillFindsTheShortRoute) {
  // An observer at the nest: ants walk every tick within 8 m, every 2 ticks to 20 m, beyond
  // every 4, each walk as far as its ticks would have taken it.
  Scene scene = loadScene(source("scenes/courtyard_ants.yaml"));
  scene.lod.enabled = true;
  scene.lod.near_radius = 8;
  scene.lod.far_radius = 20;
  scene.lod.mid_every = 2;
  scene.lod.far_every = 4;
  Colony c(scene);
  c.players = {{45.5, 44.5}};
  const double best = optimum(scene, *c.map);
  c.run(int(180 / scene.dt));
  const ColonyStats before = c.ants.stats(0);
  c.run(int(60 / scene.dt));
  const ColonyStats& s = c.ants.stats(0);
  const double recent = (s.length_sum - before.length_sum) / double(s.trips - before.trips);
  std::vector<ai::Cell> route = c.ants.trailRoute(0);
  ASSERT_FALSE(route.empty());
  const double trail = ai::pathLength(route);
  const double ratio = double(c.updates) / double(c.tick * 40);
  std::printf(
      "with LOD: %llu trips (%llu in the fourth minute, mean route %.1f m); trail route %.1f "
      "m; A* %.1f m (%.3fx, %.3fx); ant walks %.2f of every tick's\n",
      (unsigned long long)s.trips, (unsigned long long)(s.trips - before.trips), recent, trail,
      best, recent / best, trail / best, ratio);
  EXPECT_GT(s.trips - before.trips, 40u);
  EXPECT_LT(recent, 1.3 * best);  // the full-detail test's factors
  EXPECT_LT(trail, 1.25 * best);
  EXPECT_LT(ratio, 0.7);
  int on_walls = 0;
  for (std::size_t i = 0; i < c.store.size(); ++i)
    on_walls += c.map->walkable(c.store.pos[i].x(), c.store.pos[i].z()) ? 0 : 1;
  EXPECT_EQ(on_walls, 0);
}

TEST(AntMovement, UnderLodWithEveryAntNearTheWalkIsTheFullDetailWalk) {
  Scene full = loadScene(source("scenes/courtyard_ants.yaml"));
  Scene near = full;
  near.lod.enabled = true;
  near.lod.near_radius = near.lod.far_radius = 1000;
  Colony a(full), b(near);
  b.players = {{45.5, 44.5}};
  a.run(600);
  b.run(600);
  EXPECT_EQ(a.updates, b.updates);
  for (std::size_t i = 0; i < a.store.size(); ++i) EXPECT_EQ(a.store.pos[i], b.store.pos[i]) << i;
  EXPECT_EQ(a.ants.totalTrail(0), b.ants.totalTrail(0));
}

TEST(AntMovement, ANestOnAWallIsASceneError) {
  Scene scene = loadScene(source("scenes/courtyard_ants.yaml"));
  scene.npcs[0].colony.nest = {22.5, 20.5, 29};  // column 22 is a wall at row 20
  auto map = loadWorldMap(scene);
  try {
    AntMovement ants(scene, map.get());
    ADD_FAILURE() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        scene.source_path + ":29: populations[0].colony.nest: lies on a blocked cell of the map");
  }
}

}  // namespace
}  // namespace zonesim::zone
