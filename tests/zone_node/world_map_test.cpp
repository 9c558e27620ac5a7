// The scene's obstacle map as the zone systems see it: cells placed by origin and cell size,
// and the errors for a malformed map or one that reaches past the world.

#include "zone_node/world_map.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "zone_node/zone_fixture.h"

namespace zonesim::zone {
namespace {

std::string source(const std::string& relative) {
  return std::string(ZONESIM_SOURCE_DIR) + "/" + relative;
}

Scene courtyardScene(double origin_x, double origin_z, double cell) {
  Scene s = testing::npcScene(0);
  s.source_path = "probe.yaml";
  s.world = {{-50, 0, -50}, {200, 50, 200}};
  s.map.file = source("scenes/maps/courtyard.map");
  s.map.origin_x = origin_x;
  s.map.origin_z = origin_z;
  s.map.cell_size = cell;
  s.map.line = 12;
  return s;
}

std::string errorOf(const Scene& s) {
  try {
    loadWorldMap(s);
  } catch (const SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no SceneError";
  return {};
}

TEST(WorldMap, NoMapKeyGivesNoMap) {
  EXPECT_EQ(loadWorldMap(testing::npcScene(0)), nullptr);
}

TEST(WorldMap, CellsLieWhereOriginAndCellSizePutThem) {
  // courtyard.map: 64 x 64, a wall ring, a wall along column 22 with doors at rows 10-12.
  auto map = loadWorldMap(courtyardScene(-20, 10, 2.0));
  ASSERT_NE(map, nullptr);
  EXPECT_EQ(map->grid.width(), 64);
  EXPECT_EQ(map->grid.height(), 64);
  // Cell (x, y) covers world x in [-20 + 2x, -18 + 2x), z in [10 + 2y, 12 + 2y).
  EXPECT_TRUE(map->walkable(-20 + 2 * 5 + 1, 10 + 2 * 5 + 1));    // open floor
  EXPECT_FALSE(map->walkable(-20 + 2 * 22 + 1, 10 + 2 * 5 + 1));  // the wall on column 22
  EXPECT_TRUE(map->walkable(-20 + 2 * 22 + 1, 10 + 2 * 11 + 1));  // its door
  EXPECT_FALSE(map->walkable(-20 + 0.5, 10 + 2 * 5 + 1));         // the outer ring
  EXPECT_FALSE(map->walkable(-20 - 0.5, 10 + 2 * 5 + 1));         // off the map
  EXPECT_FALSE(map->walkable(-20 + 2 * 5 + 1, 10 + 128.5));       // off the map
}

TEST(WorldMap, AMapPastTheWorldNamesTheSceneLine) {
  EXPECT_EQ(errorOf(courtyardScene(100, 0, 2.0)),
            "probe.yaml:12: map.file: 64 x 64 cells of 2 m reach (228, 128), past the world's "
            "max x, z (200, 200)");
  EXPECT_NO_THROW(loadWorldMap(courtyardScene(72, 72, 2.0)));  // exactly to the corner
}

TEST(WorldMap, AMalformedMapNamesItsOwnLine) {
  std::filesystem::path bad = std::filesystem::temp_directory_path() / "zonesim_bad_world.map";
  {
    std::ofstream out(bad);
    out << "type octile\nheight 2\nwidth 3\nmap\n...\n.#\n";
  }
  Scene s = courtyardScene(0, 0, 1);
  s.map.file = bad.string();
  EXPECT_EQ(errorOf(s), bad.string() + ":6: map: row has 2 cells, expected 3");
  std::filesystem::remove(bad);
}

}  // namespace
}  // namespace zonesim::zone
