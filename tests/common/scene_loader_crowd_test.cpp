// Crowd keys of the scene (common/scene_loader_crowd.cpp): the top-level `map:` key (where the
// obstacle map lies; the grid itself is parsed by zone_node/world_map.h, tested in
// tests/zone_node/test_world_map.cpp) and an NPC population's `flow` block.

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

TEST(SceneMap, FieldsAreTakenFromTheScenesFolderAndOpenedByTheZone) {
  // Not opened here: bake_fields reads the scene to write the file in the first place.
  Scene s =
      parseScene(sceneWith("map: {file: maps/courtyard.map, fields: maps/c.fields}\n"), kSceneName);
  EXPECT_EQ(s.map.fields, sourcePath("scenes/maps/c.fields"));
  EXPECT_EQ(s.map.fields_line, 5);
  EXPECT_EQ(sceneError([] {
              parseScene(sceneWith("map: {file: maps/courtyard.map, fields: ''}\n"), kSceneName);
            }),
            kSceneName + ":5: map.fields: must not be empty");
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
            kSceneName +
                ":5: map.size: unknown key (allowed: file, origin, cell_size, doors, fields, "
                "navigation, agent_radius, static_bodies)");
}

TEST(SceneMap, NavigationChoosesThePlannerAndTheOlderKeyStillWorks) {
  const std::string agents =
      "agents:\n  types:\n    - {name: c, behaviour: travel, navigate: true, goals: [[20, 22]]}\n";
  auto planner = [&](const std::string& map_keys, const std::string& paths) {
    return parseScene(
               sceneWith("map: {file: maps/courtyard.map" + map_keys + "}\n" + agents + paths),
               kSceneName)
        .agents.paths.planner;
  };
  EXPECT_EQ(planner("", ""), AgentPlanner::AStar);
  EXPECT_EQ(planner(", navigation: navmesh", ""), AgentPlanner::NavMesh);
  EXPECT_EQ(planner(", navigation: hpa", ""), AgentPlanner::Hpa);
  EXPECT_EQ(planner(", navigation: grid", ""), AgentPlanner::AStar);
  EXPECT_EQ(planner(", navigation: jps", ""), AgentPlanner::Jps);
  EXPECT_EQ(planner(", navigation: jps", "  paths: {planner: jps}\n"), AgentPlanner::Jps);
  EXPECT_EQ(planner("", "  paths: {planner: jps}\n"), AgentPlanner::Jps);
  EXPECT_EQ(planner("", "  paths: {planner: hpa}\n"), AgentPlanner::Hpa);
  EXPECT_EQ(planner(", navigation: hpa", "  paths: {planner: hpa}\n"), AgentPlanner::Hpa);
}

TEST(SceneMap, PathAuditIsOffUnlessAsked) {
  const std::string agents =
      "map: {file: maps/courtyard.map}\n"
      "agents:\n  types:\n    - {name: c, behaviour: travel, navigate: true, goals: [[20, 22]]}\n";
  EXPECT_FALSE(parseScene(sceneWith(agents), kSceneName).agents.paths.audit);
  EXPECT_TRUE(
      parseScene(sceneWith(agents + "  paths: {audit: true}\n"), kSceneName).agents.paths.audit);
  EXPECT_EQ(
      sceneError([&] { parseScene(sceneWith(agents + "  paths: {audit: 1.5}\n"), kSceneName); }),
      kSceneName + ":9: agents.paths.audit: expected true or false, got '1.5'");
}

TEST(SceneMap, DoorsComeThroughInTimeOrderWithTheirLines) {
  Scene s = parseScene(sceneWith("map:\n"
                                 "  file: maps/courtyard.map\n"
                                 "  doors:\n"
                                 "    - {at_s: 1, cell: [22, 10]}\n"
                                 "    - {at_s: 4.5, cell: [22, 11], open: true}\n"),
                       kSceneName);
  ASSERT_EQ(s.map.doors.size(), 2u);
  EXPECT_EQ(s.map.doors[0].at_s, 1);
  EXPECT_EQ(s.map.doors[0].x, 22);
  EXPECT_EQ(s.map.doors[0].y, 10);
  EXPECT_FALSE(s.map.doors[0].open);
  EXPECT_EQ(s.map.doors[0].file, kSceneName);
  EXPECT_EQ(s.map.doors[0].line, 8);
  EXPECT_EQ(s.map.doors[1].at_s, 4.5);
  EXPECT_TRUE(s.map.doors[1].open);
  EXPECT_EQ(s.map.doors[1].line, 9);
}

TEST(SceneMap, DoorMistakesNameTheirLine) {
  auto doors = [](const std::string& list) {
    return sceneError([&] {
      parseScene(sceneWith("map:\n  file: maps/courtyard.map\n  doors:\n" + list), kSceneName);
    });
  };
  EXPECT_EQ(doors("    - {at_s: 4, cell: [1, 1]}\n    - {at_s: 2, cell: [1, 2]}\n"),
            kSceneName + ":9: map.doors[1].at_s: doors must be listed in time order");
  EXPECT_EQ(doors("    - {at_s: 4, cell: [1]}\n"),
            kSceneName + ":8: map.doors[0].cell: must be [x, y] (map column and row)");
  EXPECT_EQ(doors("    - {cell: [1, 1]}\n"),
            kSceneName + ":8: map.doors[0].at_s: required field is missing");
  EXPECT_EQ(doors("    - {at_s: 1, cell: [1, 1], shut: true}\n"),
            kSceneName + ":8: map.doors[0].shut: unknown key (allowed: at_s, cell, open)");
}

// Doors used to be agents.doors: a scene still written that way is refused, saying where they went.
TEST(SceneMap, AgentsDoorsIsRefusedAndPointsToMapDoors) {
  EXPECT_EQ(sceneError([] {
              parseScene(sceneWith("map: {file: maps/courtyard.map}\n"
                                   "agents:\n"
                                   "  types: []\n"
                                   "  doors:\n"
                                   "    - {at_s: 4, cell: [22, 10]}\n"),
                         kSceneName);
            }),
            kSceneName + ":9: agents.doors: moved to map.doors (same keys: at_s, cell, open)");
}

const std::string kMap = "map: {file: maps/courtyard.map}\n";

std::string flowScene(const std::string& flow_text, const std::string& map = kMap) {
  return sceneWith(map + "populations:\n  - kind: npc\n    count: 5\n    flow:\n" + flow_text);
}

TEST(SceneFlow, DestinationsAndDefaultsComeThrough) {
  Scene s = parseScene(flowScene("      destinations: [[1, 0, 2], [30.5, 5, 40]]\n"
                                 "      max_speed: 3\n"
                                 "      separation: {radius: 0.8}\n"),
                       kSceneName);
  ASSERT_EQ(s.npcs.size(), 1u);
  const NpcFlow& f = s.npcs[0].flow;
  EXPECT_TRUE(f.enabled);
  EXPECT_FALSE(s.npcs[0].flock.enabled);
  ASSERT_EQ(f.destinations.size(), 2u);
  EXPECT_EQ(f.destinations[1].x, 30.5);
  EXPECT_EQ(f.destinations[1].z, 40);
  EXPECT_EQ(f.destinations[1].line, 10);
  EXPECT_EQ(f.max_speed, 3);
  EXPECT_EQ(f.separation_radius, 0.8);
  EXPECT_EQ(f.separation_weight, NpcFlow{}.separation_weight);
  EXPECT_EQ(f.arrive_radius, NpcFlow{}.arrive_radius);
}

TEST(SceneFlow, ErrorsNameLineAndField) {
  auto error = [](const std::string& text) {
    return sceneError([&] { parseScene(text, kSceneName); });
  };
  EXPECT_EQ(error(flowScene("      destinations: [[1, 0, 2]]\n", "")),
            kSceneName +
                ":9: populations[0].flow.destinations: a flow-field population needs "
                "the scene's map: key");
  EXPECT_EQ(error(flowScene("      max_speed: 2\n")),
            kSceneName + ":10: populations[0].flow.destinations: required field is missing");
  EXPECT_EQ(error(flowScene("      destinations: []\n")),
            kSceneName + ":10: populations[0].flow.destinations: needs at least one destination");
  EXPECT_EQ(error(flowScene("      destinations: [[1, 0, 2], [500, 0, 2]]\n")),
            kSceneName +
                ":10: populations[0].flow.destinations[1]: x, z (500, 2) is outside "
                "the world");
  EXPECT_EQ(error(flowScene("      destinations: [[1, 0, 2]]\n      steer_rate: 0\n")),
            kSceneName + ":11: populations[0].flow.steer_rate: must be > 0, got 0");
  EXPECT_EQ(error(flowScene("      destinations: [[1, 0, 2]]\n      separation: {radius: 11}\n")),
            kSceneName +
                ":11: populations[0].flow.separation.radius: 11 m is wider than "
                "halo.width (10 m)");
  EXPECT_EQ(error(flowScene("      destinations: [[1, 0, 2]]\n    flock: {radius: 2}\n")),
            kSceneName +
                ":11: populations[0].flock: a flow-field population follows its "
                "fields, not this");
}

TEST(SceneLod, AbsentMeansOffAndValuesComeThrough) {
  EXPECT_FALSE(parseScene(sceneWith(""), kSceneName).lod.enabled);
  Scene s = parseScene(sceneWith("lod: {near_radius: 10, far_radius: 30, far_every: 4, "
                                 "far_steers: true}\n"),
                       kSceneName);
  EXPECT_TRUE(s.lod.enabled);
  EXPECT_EQ(s.lod.near_radius, 10);
  EXPECT_EQ(s.lod.far_radius, 30);
  EXPECT_EQ(s.lod.mid_every, CrowdLod{}.mid_every);
  EXPECT_EQ(s.lod.far_every, 4);
  EXPECT_TRUE(s.lod.mid_steers);
  EXPECT_TRUE(s.lod.far_steers);
  EXPECT_EQ(s.lod.crowded_count, 0);  // off unless asked
  const Scene crowded =
      parseScene(sceneWith("lod: {crowded_count: 6, crowded_cell: 2}\n"), kSceneName);
  EXPECT_EQ(crowded.lod.crowded_count, 6);
  EXPECT_EQ(crowded.lod.crowded_cell, 2);
  EXPECT_EQ(sceneError([] {
              parseScene(sceneWith("lod: {near_radius: 50, far_radius: 30}\n"), kSceneName);
            }),
            kSceneName + ":5: lod.far_radius: must be >= 50, got 30");
  EXPECT_EQ(sceneError([] { parseScene(sceneWith("lod: {mid_every: 0}\n"), kSceneName); }),
            kSceneName + ":5: lod.mid_every: must be in [1, 64], got 0");
  EXPECT_EQ(s.lod.physics_every, 1);  // bodies every tick unless asked
  EXPECT_EQ(parseScene(sceneWith("lod: {physics_every: 4}\n"), kSceneName).lod.physics_every, 4);
  EXPECT_EQ(sceneError([] { parseScene(sceneWith("lod: {physics_every: 65}\n"), kSceneName); }),
            kSceneName + ":5: lod.physics_every: must be in [1, 64], got 65");
}

TEST(SceneLod, EnabledFalseTurnsAPresentSectionOff) {
  // An overlay cannot remove its base's lod section; it can switch it off (bench/tune.py).
  EXPECT_FALSE(
      parseScene(sceneWith("lod: {enabled: false, far_every: 4}\n"), kSceneName).lod.enabled);
  EXPECT_TRUE(parseScene(sceneWith("lod: {enabled: true}\n"), kSceneName).lod.enabled);
  EXPECT_EQ(sceneError([] { parseScene(sceneWith("lod: {enabled: sometimes}\n"), kSceneName); }),
            kSceneName + ":5: lod.enabled: expected true or false, got 'sometimes'");
}

TEST(SceneLod, ObserversComeThroughAndMustLieInTheWorld) {
  EXPECT_TRUE(parseScene(sceneWith("lod: {}\n"), kSceneName).lod.observers.empty());
  Scene s = parseScene(sceneWith("lod:\n  observers: [[1, 0, 2], [30, 5, -4]]\n"), kSceneName);
  ASSERT_EQ(s.lod.observers.size(), 2u);
  EXPECT_EQ(s.lod.observers[0], (std::pair<double, double>{1, 2}));
  EXPECT_EQ(s.lod.observers[1], (std::pair<double, double>{30, -4}));
  EXPECT_EQ(sceneError([] {
              parseScene(sceneWith("lod:\n  observers:\n    - [1, 0, 2]\n    - [1, 0, 200]\n"),
                         kSceneName);
            }),
            kSceneName + ":8: lod.observers[1]: x, z (1, 200) is outside the world");
}

// A flocking population with `goal_text` under its flock key.
std::string flockScene(const std::string& goal_text) {
  return sceneWith(
      "halo: {width: 10}\npopulations:\n  - kind: npc\n    count: 10\n    flock:\n"
      "      max_speed: 3\n" +
      goal_text);
}

TEST(SceneFlockGoal, AbsentMeansNoGoalAndValuesComeThrough) {
  NpcFlock none = parseScene(flockScene(""), kSceneName).npcs[0].flock;
  EXPECT_FALSE(none.has_goal);
  NpcFlock f =
      parseScene(flockScene("      goal: {point: [40, 0, 60], weight: 0.5, slow_radius: 8}\n"),
                 kSceneName)
          .npcs[0]
          .flock;
  EXPECT_TRUE(f.has_goal);
  EXPECT_EQ(f.goal_x, 40);
  EXPECT_EQ(f.goal_z, 60);
  EXPECT_EQ(f.goal_weight, 0.5);
  EXPECT_EQ(f.goal_speed, 3);  // max_speed unless given
  EXPECT_EQ(f.goal_slow_radius, 8);
  EXPECT_EQ(parseScene(flockScene("      goal: {point: [0, 0, 0], speed: 1.5}\n"), kSceneName)
                .npcs[0]
                .flock.goal_speed,
            1.5);
}

TEST(SceneFlockGoal, ErrorsNameLineAndField) {
  auto error = [](const std::string& text) {
    return sceneError([&] { parseScene(text, kSceneName); });
  };
  EXPECT_EQ(error(flockScene("      goal: {weight: 1}\n")),
            kSceneName + ":11: populations[0].flock.goal.point: required field is missing");
  EXPECT_EQ(
      error(flockScene("      goal:\n        point: [500, 0, 0]\n")),
      kSceneName + ":12: populations[0].flock.goal.point: x, z (500, 0) is outside the world");
  EXPECT_EQ(
      error(flockScene("      goal: {point: [1, 0, 1], speed: 4}\n")),
      kSceneName + ":11: populations[0].flock.goal.speed: 4 m/s is above flock.max_speed (3 m/s)");
  EXPECT_EQ(error(flockScene("      goal: {point: [1, 0, 1], weight: -1}\n")),
            kSceneName + ":11: populations[0].flock.goal.weight: must be >= 0, got -1");
}

}  // namespace
}  // namespace zonesim

namespace zonesim {
namespace {

std::string groupScene(const std::string& key, const std::string& text,
                       const std::string& map = kMap) {
  return sceneWith(map + "populations:\n  - kind: npc\n    count: 6\n    " + key + ":\n" + text);
}

TEST(SceneFormation, RouteAndDefaultsComeThrough) {
  Scene s = parseScene(groupScene("formation",
                                  "      route: [[1, 0, 2], [30.5, 5, 40]]\n"
                                  "      columns: 3\n"
                                  "      separation: {radius: 0.8}\n"),
                       kSceneName);
  const NpcFormation& f = s.npcs[0].formation;
  EXPECT_TRUE(f.enabled);
  ASSERT_EQ(f.route.size(), 2u);
  EXPECT_EQ(f.route[1].x, 30.5);
  EXPECT_EQ(f.route[1].z, 40);
  EXPECT_EQ(f.route[1].line, 10);
  EXPECT_EQ(f.columns, 3);
  EXPECT_EQ(f.separation_radius, 0.8);
  EXPECT_EQ(f.spacing, NpcFormation{}.spacing);
  EXPECT_EQ(f.cut_off, NpcFormation{}.cut_off);
}

TEST(SceneFormation, ErrorsNameLineAndField) {
  auto error = [](const std::string& text) {
    return sceneError([&] { parseScene(text, kSceneName); });
  };
  EXPECT_EQ(
      error(groupScene("formation", "      route: [[1, 0, 2]]\n", "")),
      kSceneName + ":9: populations[0].formation.route: a formation needs the scene's map: key");
  EXPECT_EQ(error(groupScene("formation", "      route: []\n")),
            kSceneName +
                ":10: populations[0].formation.route: needs at least one point (where the "
                "centre starts)");
  EXPECT_EQ(
      error(groupScene("formation", "      route: [[1, 0, 2], [500, 0, 2]]\n")),
      kSceneName + ":10: populations[0].formation.route[1]: x, z (500, 2) is outside the world");
  EXPECT_EQ(error(groupScene("formation", "      route: [[1, 0, 2]]\n      max_speed: 1\n")),
            kSceneName +
                ":11: populations[0].formation.max_speed: 1 m/s is not above centre_speed "
                "(1.5 m/s)");
  EXPECT_EQ(error(groupScene("formation", "      route: [[1, 0, 2]]\n      rejoin: 6\n")),
            kSceneName + ":11: populations[0].formation.rejoin: 6 m is not below cut_off (5 m)");
  EXPECT_EQ(error(groupScene("formation", "      route: [[1, 0, 2]]\n      columns: 0\n")),
            kSceneName + ":11: populations[0].formation.columns: must be in [1, 64], got 0");
  EXPECT_EQ(
      error(groupScene("formation", "      route: [[1, 0, 2]]\n    gather: {point: [1, 0, 2]}\n")),
      kSceneName +
          ":11: populations[0].gather: a formation population holds its slots, not "
          "this");
}

TEST(SceneColony, ValuesAndDefaultsComeThrough) {
  Scene s = parseScene(groupScene("colony",
                                  "      nest: [1, 0, 2]\n"
                                  "      food: [30.5, 0, 40]\n"
                                  "      evaporation: 0.1\n"
                                  "      food_until: 60\n"),
                       kSceneName);
  const NpcColony& c = s.npcs[0].colony;
  EXPECT_TRUE(c.enabled);
  EXPECT_EQ(c.nest.x, 1);
  EXPECT_EQ(c.food.z, 40);
  EXPECT_EQ(c.food.line, 11);
  EXPECT_EQ(c.evaporation, 0.1);
  EXPECT_EQ(c.food_until, 60);
  EXPECT_EQ(c.alpha, NpcColony{}.alpha);
  EXPECT_EQ(c.beta, NpcColony{}.beta);
}

TEST(SceneColony, ErrorsNameLineAndField) {
  auto error = [](const std::string& text) {
    return sceneError([&] { parseScene(text, kSceneName); });
  };
  EXPECT_EQ(
      error(groupScene("colony", "      nest: [1, 0, 2]\n      food: [3, 0, 4]\n", "")),
      kSceneName + ":9: populations[0].colony.nest: an ant colony needs the scene's map: key");
  EXPECT_EQ(error(groupScene("colony", "      nest: [1, 0, 2]\n")),
            kSceneName + ":10: populations[0].colony.food: required field is missing");
  EXPECT_EQ(error(groupScene("colony",
                             "      nest: [1, 0, 2]\n      food: [3, 0, 4]\n"
                             "      evaporation: 2\n")),
            kSceneName + ":12: populations[0].colony.evaporation: must be in [0, 1], got 2");
  EXPECT_EQ(error(groupScene("colony", "      nest: [1, 0, 2]\n      food: [3, 0, 400]\n")),
            kSceneName + ":11: populations[0].colony.food: x, z (3, 400) is outside the world");
}

}  // namespace
}  // namespace zonesim
