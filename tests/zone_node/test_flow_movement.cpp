// Flow-field crowds in a zone (zone_node/systems/flow_movement.h) on the shipped courtyard
// scene: every NPC reaches its destination without ever standing on a wall, destinations spread
// over the NPCs, and a destination on a wall is a scene error.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "zone_node/population.h"
#include "zone_node/systems/flow_movement.h"
#include "zone_node/world_map.h"

namespace zonesim::zone {
namespace {

std::string source(const std::string& relative) {
  return std::string(ZONESIM_SOURCE_DIR) + "/" + relative;
}

TEST(FlowMovement, EveryNpcOfTheCourtyardReachesItsDestination) {
  Scene scene = loadScene(source("scenes/courtyard_flow.yaml"));
  auto map = loadWorldMap(scene);
  ASSERT_NE(map, nullptr);
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  ASSERT_EQ(store.size(), 400u);
  FlowMovement flows(scene, map.get());
  ASSERT_TRUE(flows.active());
  const NpcFlow& f = scene.npcs[0].flow;
  // Upper bound: the longest octile route on the 64 m courtyard is under 130 m, at 2 m/s,
  // doubled for the queues at the doors.
  const int max_ticks = int(std::ceil(2 * 130 / f.max_speed / scene.dt));
  int tick = 0, on_walls = 0;
  std::size_t walking = store.size();
  for (; tick < max_ticks && walking > 0; ++tick) {
    walking = flows.step(store, nullptr, scene.dt);
    for (std::size_t i = 0; i < store.size(); ++i)
      on_walls += map->walkable(store.pos[i].x(), store.pos[i].z()) ? 0 : 1;
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

TEST(FlowMovement, DestinationsSpreadOverTheNpcs) {
  std::vector<int> count(3);
  for (std::uint64_t id = 1; id <= 3000; ++id) ++count[std::size_t(flowDestination(id, 3))];
  for (int c : count) EXPECT_NEAR(c, 1000, 100);
  for (std::uint64_t id = 1; id <= 100; ++id) EXPECT_EQ(flowDestination(id, 1), 0);
}

TEST(FlowMovement, ADestinationOnAWallIsASceneError) {
  Scene scene = loadScene(source("scenes/courtyard_flow.yaml"));
  scene.npcs[0].flow.destinations[1] = {22.5, 20.5, 31};  // column 22 is a wall at row 20
  auto map = loadWorldMap(scene);
  try {
    FlowMovement flows(scene, map.get());
    ADD_FAILURE() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              scene.source_path +
                  ":31: populations[0].flow.destinations[1]: lies on a blocked cell of the map");
  }
}

}  // namespace
}  // namespace zonesim::zone
