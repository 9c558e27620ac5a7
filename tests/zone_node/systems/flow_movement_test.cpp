// Flow-field crowds in a zone (zone_node/systems/flow_movement.h) on the shipped courtyard
// scene: every NPC reaches its destination without ever standing on a wall, destinations spread
// over the NPCs, and a destination on a wall is a scene error. With bodies kept apart no tick
// makes a new overlap or deepens one, and most NPCs still arrive. Each NPC's arrival is
// reported once, in the step that took it there (zone_node --arrivals).

#include "zone_node/systems/flow_movement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "common/scene.h"
#include "crowd/vec2.h"
#include "zone_node/population.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/world_map.h"
#include "zone_node/zone_map.h"

namespace zonesim::zone {
namespace {

std::string source(const std::string& relative) {
  return std::string(ZONESIM_SOURCE_DIR) + "/" + relative;
}

// A shipped scene, its map and its initial entities (kept in place: the map reads the scene).
struct ShippedScene {
  Scene scene;
  std::unique_ptr<ZoneMap> map;
  EntityStore store;
  explicit ShippedScene(const std::string& relative)
      : scene(loadScene(source(relative))), map(ZoneMap::load(scene)) {
    forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  }
};

TEST(FlowMovement, EveryNpcOfTheCourtyardReachesItsDestination) {
  ShippedScene courtyard("scenes/courtyard_flow.yaml");
  const Scene& scene = courtyard.scene;
  const std::unique_ptr<ZoneMap>& map = courtyard.map;
  ASSERT_NE(map, nullptr);
  EntityStore& store = courtyard.store;
  ASSERT_EQ(store.size(), 400u);
  FlowMovement flows(scene, map.get());
  ASSERT_TRUE(flows.active());
  const NpcFlow& f = scene.npcs[0].flow;
  // Upper bound: the longest octile route on the 64 m courtyard is under 130 m, at 2 m/s,
  // doubled for the queues at the doors.
  const int max_ticks = int(std::ceil(2 * 130 / f.max_speed / scene.dt));
  int tick = 0, on_walls = 0;
  std::size_t walking = store.size();
  LoneZone lone{scene.dt};
  for (; tick < max_ticks && walking > 0; ++tick) {
    lone.step(flows, store, std::uint64_t(tick));
    walking = flows.walking();
    for (std::size_t i = 0; i < store.size(); ++i)
      on_walls += map->world().walkable(store.pos[i].x(), store.pos[i].z()) ? 0 : 1;
  }
  std::printf("all %zu NPCs arrived after %.1f s (bound %.1f s)\n", store.size() - walking,
              tick * scene.dt, max_ticks * scene.dt);
  EXPECT_EQ(walking, 0u);
  EXPECT_EQ(on_walls, 0);
  for (std::size_t i = 0; i < store.size(); ++i) {
    ASSERT_TRUE(flows.arrived(store, i)) << i;
    // Arrived means within the arrival radius of the centre of its destination's cell.
    const NpcFlow::Destination& d =
        f.destinations[std::size_t(flowDestination(store.id[i].value, 3))];
    double cx = std::floor(d.x) + 0.5, cz = std::floor(d.z) + 0.5;
    EXPECT_LE(std::hypot(store.pos[i].x() - cx, store.pos[i].z() - cz), f.arrive_radius);
    EXPECT_EQ(store.vel[i].norm(), 0.0);
  }
}

TEST(FlowMovement, EachArrivalIsReportedOnceInTheStepThatTookTheNpcThere) {
  ShippedScene courtyard("scenes/courtyard_flow.yaml");
  EntityStore& store = courtyard.store;
  FlowMovement flows(courtyard.scene, courtyard.map.get());
  LoneZone lone{courtyard.scene.dt};
  std::map<std::uint64_t, int> reported;  // id -> times reported
  std::size_t arrived_before = 0;
  // 300 ticks (15 s): the nearest NPCs have arrived, most are still walking.
  for (int tick = 0; tick < 300; ++tick) {
    std::vector<std::uint8_t> was(store.size());
    for (std::size_t i = 0; i < store.size(); ++i) was[i] = flows.arrived(store, i) ? 1 : 0;
    lone.step(flows, store, std::uint64_t(tick));
    std::map<std::uint64_t, int> now;
    for (std::size_t i = 0; i < store.size(); ++i)
      if (flows.arrived(store, i) && !was[i]) now[store.id[i].value] = 1;
    std::map<std::uint64_t, int> said;
    for (std::uint64_t id : flows.arrivedLastStep()) ++said[id];
    ASSERT_EQ(said, now) << "tick " << tick;
    for (const auto& [id, n] : said) reported[id] += n;
    arrived_before = store.size() - flows.walking();
  }
  std::printf("%zu of %zu NPCs arrived in 300 ticks\n", reported.size(), store.size());
  EXPECT_GT(reported.size(), 20u);
  EXPECT_LT(reported.size(), store.size());
  EXPECT_EQ(reported.size(), arrived_before);  // none of the courtyard's NPCs starts arrived
  for (const auto& [id, n] : reported) EXPECT_EQ(n, 1) << id;
}

TEST(FlowMovement, BodiesKeptApartMakeNoNewOverlapAndMostStillArrive) {
  ShippedScene courtyard("scenes/courtyard_flow_bodies.yaml");
  const Scene& scene = courtyard.scene;
  const std::unique_ptr<ZoneMap>& map = courtyard.map;
  ASSERT_NE(map, nullptr);
  EntityStore& store = courtyard.store;
  FlowMovement flows(scene, map.get());
  const NpcFlow& f = scene.npcs[0].flow;
  ASSERT_EQ(f.body_radius, 0.3);
  // The deepest overlap between NPCs still walking (arrived ones have left the crowd), by
  // brute force over every pair.
  const auto deepest = [&] {
    double depth = 0;
    for (std::size_t i = 0; i < store.size(); ++i) {
      if (flows.arrived(store, i)) continue;
      for (std::size_t j = i + 1; j < store.size(); ++j) {
        if (flows.arrived(store, j)) continue;
        const double d =
            std::hypot(store.pos[i].x() - store.pos[j].x(), store.pos[i].z() - store.pos[j].z());
        depth = std::max(depth, 2 * f.body_radius - d);
      }
    }
    return depth;
  };
  const double spawned = deepest();
  EXPECT_GT(spawned, 0.1);  // the spawn overlaps: there is something to back off from
  const int max_ticks = int(std::ceil(2 * 130 / f.max_speed / scene.dt));
  int tick = 0, deepened = 0;
  std::size_t walking = store.size();
  double before = spawned, after_1s = 0;
  LoneZone lone{scene.dt};
  for (; tick < max_ticks && walking > 0; ++tick) {
    lone.step(flows, store, std::uint64_t(tick));
    walking = flows.walking();
    const double now = deepest();
    deepened += now > std::max(before, 0.0) + 1e-9;
    if (tick * scene.dt >= 1.0) after_1s = std::max(after_1s, now);
    before = now;
  }
  std::printf("spawn overlap %.4f m, deepest after 1 s %.6f m; all %zu NPCs arrived after %.1f s\n",
              spawned, after_1s, store.size() - walking, tick * scene.dt);
  EXPECT_EQ(deepened, 0);
  EXPECT_LE(after_1s, 0.01);  // the spawn's overlaps are gone within a second
  // Bodies that cannot pass through each other can clog a doorway that two flows cross in
  // opposite ways: 357 of 400 arrived when written (all 400 without bodies, in 38.7 s).
  EXPECT_GE(store.size() - walking, 340u);
}

TEST(FlowMovement, TheCrowdGoesRoundADoorThatCloses) {
  // The hall's north door (column 22, rows 10-12) shuts at 3 s, while NPCs are on their way
  // through it: the fields are rebuilt, nobody steps into the doorway afterwards (those caught
  // in it step out), nobody stands on a wall, and every NPC still arrives, by the south door.
  Scene scene = loadScene(source("scenes/courtyard_flow.yaml"));
  for (int y = 10; y <= 12; ++y) {
    MapDoor d;
    d.at_s = 3.0;
    d.x = 22;
    d.y = y;
    scene.map.doors.push_back(d);
  }
  std::unique_ptr<ZoneMap> map = ZoneMap::load(scene);
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  FlowMovement flows(scene, map.get());
  auto cellAt = [&](std::size_t i) {
    return map->world().frame.cellOf({store.pos[i].x(), store.pos[i].z()});
  };
  auto inDoor = [&](std::size_t i) {
    ai::Cell c = cellAt(i);
    return c.x == 22 && c.y >= 10 && c.y <= 12;
  };
  const int max_ticks = int(std::ceil(2 * 130 / scene.npcs[0].flow.max_speed / scene.dt));
  int tick = 0, rebuilt = 0, entered = 0, on_walls = 0, through_before = 0;
  std::vector<char> was_in(store.size(), 0);
  std::size_t walking = store.size();
  LoneZone lone{scene.dt};
  for (; tick < max_ticks && walking > 0; ++tick) {
    double time = tick * scene.dt;
    map->applyDoors(time);  // as the zone does at the start of its AI phase
    lone.step(flows, store, std::uint64_t(tick));
    rebuilt += flows.fieldsRebuilt();
    walking = flows.walking();
    for (std::size_t i = 0; i < store.size(); ++i) {
      bool in = inDoor(i);
      if (time < 3.0) through_before += in && !was_in[i];
      if (time >= 3.0 && in && !was_in[i]) ++entered;
      was_in[i] = in;
      ai::Cell c = cellAt(i);
      if (!in && !flows.grid()->passable(c.x, c.y)) ++on_walls;
    }
  }
  std::printf(
      "door shut at 3 s: %d fields rebuilt, %d NPCs had entered it before, all arrived "
      "after %.1f s\n",
      rebuilt, through_before, tick * scene.dt);
  EXPECT_EQ(rebuilt, 3);         // one field per destination
  EXPECT_GT(through_before, 0);  // the door was in use when it shut
  EXPECT_EQ(entered, 0);
  EXPECT_EQ(on_walls, 0);
  EXPECT_EQ(walking, 0u);
}

TEST(FlowMovement, DestinationsSpreadOverTheNpcs) {
  std::vector<int> count(3);
  for (std::uint64_t id = 1; id <= 3000; ++id) ++count[std::size_t(flowDestination(id, 3))];
  for (int c : count) EXPECT_NEAR(c, 1000, 100);
  for (std::uint64_t id = 1; id <= 100; ++id) EXPECT_EQ(flowDestination(id, 1), 0);
}

TEST(FlowMovement, ADestinationOnAWallIsASceneError) {
  Scene scene = loadScene(source("scenes/courtyard_flow.yaml"));
  scene.npcs[0].flow.destinations[1] = {22.5, 20.5, 31};  // column 22 is a wall at row 20
  std::unique_ptr<ZoneMap> map = ZoneMap::load(scene);
  try {
    FlowMovement flows(scene, map.get());
    ADD_FAILURE() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              scene.source_path +
                  ":31: populations[0].flow.destinations[1]: lies on a blocked cell of the map");
  }
}

// Runs the courtyard crowd to the end; per NPC (by id) the tick it arrived. Counts NPC updates.
std::map<std::uint64_t, int> arrivalTicks(const Scene& scene, std::span<const crowd::Vec2> players,
                                          std::size_t& updates) {
  std::unique_ptr<ZoneMap> map = ZoneMap::load(scene);
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  FlowMovement flows(scene, map.get());
  std::map<std::uint64_t, int> arrived;
  updates = 0;
  LoneZone lone{scene.dt};
  lone.players.assign(players.begin(), players.end());
  for (int tick = 0; tick < 4000 && arrived.size() < store.size(); ++tick) {
    lone.step(flows, store, std::uint64_t(tick));
    updates += flows.updates();
    for (std::size_t i = 0; i < store.size(); ++i)
      if (flows.arrived(store, i)) arrived.emplace(store.id[i].value, tick + 1);
  }
  return arrived;
}

TEST(FlowMovement, LevelOfDetailReachesTheSameOutcome) {
  // A player in the west hall: NPCs near it update every tick, the rest of the courtyard every
  // 2 or 8 ticks (the far ones without separation). Every NPC still arrives, and its arrival
  // time moves little (LOD steps catch up the time they skip, and arrival is checked each
  // update, so an NPC arrives at most one period late).
  Scene scene = loadScene(source("scenes/courtyard_flow.yaml"));
  std::vector<crowd::Vec2> players{{8.0, 40.0}};
  std::size_t full_updates = 0, lod_updates = 0;
  auto full = arrivalTicks(scene, players, full_updates);
  scene.lod.enabled = true;
  scene.lod.near_radius = 12;
  scene.lod.far_radius = 30;
  auto lod = arrivalTicks(scene, players, lod_updates);
  ASSERT_EQ(full.size(), 400u);
  ASSERT_EQ(lod.size(), 400u);
  double sum = 0, worst = 0, mean_full = 0;
  for (auto [id, t] : full) {
    double d = std::abs(lod.at(id) - t) * scene.dt;
    sum += d;
    worst = std::max(worst, d);
    mean_full += t * scene.dt;
  }
  mean_full /= full.size();
  std::printf(
      "updates %zu full, %zu with LOD (%.2fx fewer); arrival time moved %.2f s on "
      "average (mean arrival %.1f s), %.1f s at worst\n",
      full_updates, lod_updates, double(full_updates) / lod_updates, sum / full.size(), mean_full,
      worst);
  EXPECT_LT(lod_updates, full_updates / 2);
  EXPECT_LT(sum / full.size(), 0.1 * mean_full);
}

// Issue 19's idle work: once every NPC has arrived the crowd sleeps and a step looks at none of
// them (nor moves any), until an entity comes to the zone; a walking newcomer wakes the crowd,
// which then takes it to its destination and sleeps again.
TEST(FlowMovement, AnArrivedCrowdSleepsUntilANewcomerWakesIt) {
  ShippedScene courtyard("scenes/courtyard_flow.yaml");
  EntityStore& store = courtyard.store;
  const EntityRecordData first = store.record(0);  // where it starts: far from its goal
  FlowMovement flows(courtyard.scene, courtyard.map.get());
  LoneZone lone{courtyard.scene.dt};
  std::uint64_t tick = 0;
  for (; tick < 3000 && (tick == 0 || flows.walking() > 0); ++tick) {
    lone.step(flows, store, tick);
    EXPECT_EQ(lone.counters.flow_npcs_visited, flows.visited());
  }
  ASSERT_EQ(flows.walking(), 0u) << "the courtyard did not arrive in 3000 ticks";
  // The step that found the last arrival looked at everyone; from the next one on, nobody.
  EXPECT_EQ(flows.visited(), store.size());
  const std::vector<Vec3> rest = store.pos;
  for (int k = 0; k < 100; ++k, ++tick) {
    lone.step(flows, store, tick);
    ASSERT_EQ(flows.visited(), 0u) << "tick " << tick;
    ASSERT_EQ(lone.counters.flow_npcs_visited, 0u);
    ASSERT_EQ(flows.sleeping(), 1u);
    ASSERT_EQ(flows.updates(), 0u);
  }
  EXPECT_EQ(store.pos, rest);
  // A newcomer of the same population, where the first NPC started.
  EntityRecordData newcomer = first;
  newcomer.id = EntityId{1'000'000};
  store.add(newcomer);
  lone.step(flows, store, tick++);
  EXPECT_EQ(flows.sleeping(), 0u);
  EXPECT_EQ(flows.visited(), store.size());
  EXPECT_EQ(flows.walking(), 1u);
  EXPECT_EQ(flows.updates(), 1u);
  const std::size_t at = *store.indexOf(newcomer.id);
  EXPECT_NE(store.pos[at], newcomer.pos);
  for (int k = 0; k < 3000 && flows.walking() > 0; ++k) lone.step(flows, store, tick++);
  EXPECT_TRUE(flows.arrived(store, at));
  lone.step(flows, store, tick++);
  EXPECT_EQ(flows.visited(), 0u);
  for (std::size_t i = 0; i < rest.size(); ++i) EXPECT_EQ(store.pos[i], rest[i]) << i;
}

}  // namespace
}  // namespace zonesim::zone
