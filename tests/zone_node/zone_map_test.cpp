#include "zone_node/zone_map.h"

#include <gtest/gtest.h>

#include <string>

#include "common/scene.h"
#include "zone_node/zone_fixture.h"
#include "zone_node/zone_node.h"

namespace zonesim::zone {
namespace {

std::string source(const std::string& relative) {
  return std::string(ZONESIM_SOURCE_DIR) + "/" + relative;
}

MapDoor door(double at_s, int x, int y, bool open) {
  MapDoor d;
  d.at_s = at_s;
  d.x = x;
  d.y = y;
  d.open = open;
  d.file = "doors.yaml";
  d.line = 7;
  return d;
}

// The east yard's wall (row 32 of the courtyard) has gaps at columns 36-38 and 53-62.
constexpr int kWallRow = 32, kGapFrom = 36, kGapTo = 38;

Scene withWestGapShut(const std::string& scene_file) {
  Scene scene = loadScene(source(scene_file));
  for (int x = kGapFrom; x <= kGapTo; ++x)
    scene.map.doors.push_back(door(0.0, x, kWallRow, false));
  return scene;
}

bool inWestGap(const WorldMap& map, const EntityStore& store, std::size_t i) {
  ai::Cell c = map.frame.cellOf({store.pos[i].x(), store.pos[i].z()});
  return c.y == kWallRow && c.x >= kGapFrom && c.x <= kGapTo;
}

TEST(ZoneMap, DoorsChangeTheOneMapAtTheirTimeAndSayWhetherTheyChangedACell) {
  Scene scene = loadScene(source("scenes/courtyard_flow.yaml"));
  std::unique_ptr<ZoneMap> map = ZoneMap::load(scene);
  ASSERT_NE(map, nullptr);
  ASSERT_TRUE(map->world().grid.passable(37, kWallRow));
  ZoneMap doors(map->world(), {door(1.0, 37, kWallRow, false), door(1.0, 37, kWallRow, false),
                               door(2.0, 37, kWallRow, true)});
  EXPECT_TRUE(doors.applyDoors(0.5).empty());
  EXPECT_TRUE(doors.world().grid.passable(37, kWallRow));
  auto due = doors.applyDoors(1.0);
  ASSERT_EQ(due.size(), 2u);
  EXPECT_TRUE(due[0].changed);
  EXPECT_FALSE(due[1].changed) << "already shut by the first";
  EXPECT_TRUE(doors.changedNow());
  EXPECT_FALSE(doors.world().grid.passable(37, kWallRow));
  EXPECT_TRUE(doors.applyDoors(1.5).empty());
  EXPECT_FALSE(doors.changedNow());
  ASSERT_EQ(doors.applyDoors(2.0).size(), 1u);
  EXPECT_TRUE(doors.world().grid.passable(37, kWallRow));
}

TEST(ZoneMap, ADoorOffTheMapIsASceneErrorWithItsLine) {
  Scene scene = loadScene(source("scenes/courtyard_flow.yaml"));
  std::unique_ptr<ZoneMap> map = ZoneMap::load(scene);
  ASSERT_NE(map, nullptr);
  try {
    ZoneMap doors(map->world(), {door(1.0, 64, 3, false)});
    ADD_FAILURE() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "doors.yaml:7: map.doors: cell (64, 3) is off the 64x64 map");
  }
}

// Ants and formation members walk on the zone's map, so they see its doors (they walked on a
// copy of the map without doors before the zone owned one map).
std::uint64_t ticksWithSomeoneInTheWestGap(const Scene& scene, int ticks) {
  ZoneNode node(scene, MPI_COMM_WORLD, testing::localZone(1));
  std::uint64_t seen = 0;
  for (int t = 0; t < ticks; ++t) {
    node.tick();
    for (std::size_t i = 0; i < node.store().size(); ++i)
      if (inWestGap(*node.worldMap(), node.store(), i)) {
        ++seen;
        break;
      }
  }
  return seen;
}

TEST(ZoneMap, AntsDoNotWalkThroughAShutDoor) {
  Scene open = loadScene(source("scenes/courtyard_ants.yaml"));
  ASSERT_GT(ticksWithSomeoneInTheWestGap(open, 1200), 0u) << "ants use the gap when it is open";
  EXPECT_EQ(ticksWithSomeoneInTheWestGap(withWestGapShut("scenes/courtyard_ants.yaml"), 1200), 0u);
}

TEST(ZoneMap, FormationMembersDoNotStandInAShutDoor) {
  Scene open = loadScene(source("scenes/courtyard_formation.yaml"));
  ASSERT_GT(ticksWithSomeoneInTheWestGap(open, 1400), 0u) << "the route goes through the gap";
  EXPECT_EQ(ticksWithSomeoneInTheWestGap(withWestGapShut("scenes/courtyard_formation.yaml"), 1400),
            0u);
}

}  // namespace
}  // namespace zonesim::zone
