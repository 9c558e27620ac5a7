// The top-level `map:` key: where the obstacle map lies and the errors for a bad one. The grid
// itself is parsed by zone_node/world_map.h (tests/zone_node/test_world_map.cpp).

#include <gtest/gtest.h>

#include <string>

#include "common/scene.h"
#include "scene_test_util.h"

namespace zonesim {
namespace {

using test::sceneError;
using test::sourcePath;

// A scene "in" scenes/ (relative map paths resolve against its folder) with `map_text`.
std::string sceneWith(const std::string& map_text) {
  return "world: {min: [-10, 0, -20], max: [100, 10, 100]}\n"
         "tick: {dt: 0.05}\n"
         "seed: 1\n"
         "zones: {columns: 2, rows: 1}\n" +
         map_text;
}

const std::string kSceneName = sourcePath("scenes/probe.yaml");

TEST(SceneMap, AbsentMeansNoMap) {
  Scene s = parseScene(sceneWith(""), kSceneName);
  EXPECT_FALSE(s.map.present());
}

TEST(SceneMap, DefaultsPlaceCellZeroAtTheWorldsMinimum) {
  Scene s = parseScene(sceneWith("map:\n  file: maps/courtyard.map\n"), kSceneName);
  ASSERT_TRUE(s.map.present());
  EXPECT_EQ(s.map.file, sourcePath("scenes/maps/courtyard.map"));
  EXPECT_EQ(s.map.origin_x, -10);
  EXPECT_EQ(s.map.origin_z, -20);
  EXPECT_EQ(s.map.cell_size, 1);
  EXPECT_EQ(s.map.line, 6);
}

TEST(SceneMap, OriginAndCellSizeComeThrough) {
  Scene s = parseScene(
      sceneWith("map: {file: maps/courtyard.map, origin: [2, 0, 3.5], cell_size: 0.5}\n"),
      kSceneName);
  EXPECT_EQ(s.map.origin_x, 2);
  EXPECT_EQ(s.map.origin_z, 3.5);
  EXPECT_EQ(s.map.cell_size, 0.5);
}

TEST(SceneMap, AbsolutePathsStayAsGiven) {
  std::string abs = sourcePath("tests/data/movingai/8room_000.map");
  Scene s = parseScene(sceneWith("map: {file: " + abs + "}\n"), kSceneName);
  EXPECT_EQ(s.map.file, abs);
}

TEST(SceneMap, ErrorsNameLineAndField) {
  EXPECT_EQ(
      sceneError([] { parseScene(sceneWith("map: {file: maps/nothing.map}\n"), kSceneName); }),
      kSceneName + ":5: map.file: cannot open map file '" + sourcePath("scenes/maps/nothing.map") +
          "'");
  EXPECT_EQ(sceneError([] { parseScene(sceneWith("map: {file: maps}\n"), kSceneName); }),
            kSceneName + ":5: map.file: cannot open map file '" + sourcePath("scenes/maps") + "'");
  EXPECT_EQ(sceneError([] { parseScene(sceneWith("map: {cell_size: 1}\n"), kSceneName); }),
            kSceneName + ":5: map.file: required field is missing");
  EXPECT_EQ(sceneError([] {
              parseScene(sceneWith("map:\n  file: maps/courtyard.map\n  cell_size: 0\n"),
                         kSceneName);
            }),
            kSceneName + ":7: map.cell_size: must be > 0, got 0");
  EXPECT_EQ(sceneError([] {
              parseScene(sceneWith("map:\n  file: maps/courtyard.map\n  origin: [0, 0, 200]\n"),
                         kSceneName);
            }),
            kSceneName + ":7: map.origin: x, z (0, 200) is outside the world");
  EXPECT_EQ(sceneError([] {
              parseScene(sceneWith("map: {file: maps/courtyard.map, size: 3}\n"), kSceneName);
            }),
            kSceneName + ":5: map.size: unknown key (allowed: file, origin, cell_size)");
}

}  // namespace
}  // namespace zonesim
