// Scene files that must be rejected, each with the exact "file:line: field: problem" message.
// The broken files in tests/data/scenes_bad/ carry their expected message in a first-line
// comment "# expect-error: LINE: FIELD: PROBLEM", so adding a case is adding a file.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include "common/scene.h"
#include "scene_test_util.h"

namespace zonesim {
namespace {

using test::sceneError;
using test::sourcePath;

std::vector<std::string> badSceneFiles() {
  return test::yamlStems("tests/data/scenes_bad");
}

class BadSceneFile : public ::testing::TestWithParam<std::string> {};

TEST_P(BadSceneFile, FailsWithTheMessageItDeclares) {
  std::string path = sourcePath("tests/data/scenes_bad/" + GetParam() + ".yaml");
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  const std::string tag = "# expect-error: ";
  ASSERT_EQ(header.rfind(tag, 0), 0u) << path << " lacks an expect-error first line";
  EXPECT_EQ(sceneError([&] { loadScene(path); }), path + ":" + header.substr(tag.size()));
}

INSTANTIATE_TEST_SUITE_P(Files, BadSceneFile, ::testing::ValuesIn(badSceneFiles()),
                         [](const auto& info) { return info.param; });

TEST(BadSceneFiles, CoverEveryKindOfMistake) {
  std::vector<std::string> stems = badSceneFiles();
  for (const char* wanted : {"unknown_key", "wrong_type", "scalar_for_list", "negative_count",
                             "missing_seed", "bad_yaml", "unknown_kind"}) {
    EXPECT_NE(std::find(stems.begin(), stems.end(), wanted), stems.end()) << wanted;
  }
}

// Lines 1-4; each case appends from line 5. Zones are 50 m x 50 m.
constexpr const char* kBase =
    "world: {min: [0, 0, 0], max: [100, 10, 100]}\n"
    "tick: {dt: 0.05}\n"
    "seed: 1\n"
    "zones: {columns: 2, rows: 2}\n";

struct InlineCase {
  const char* label;
  std::string text;
  std::string message;  ///< what() after "inline.yaml:"
};

// Names the case in gtest output instead of dumping its bytes.
void PrintTo(const InlineCase& c, std::ostream* os) {
  *os << c.label;
}

std::string withBase(const char* extra) {
  return std::string(kBase) + extra;
}

const InlineCase kInlineCases[] = {
    {"negative_halo", withBase("halo:\n  width: -1\n"), "6: halo.width: must be >= 0, got -1"},
    {"negative_skin", withBase("halo:\n  skin: -1\n"), "6: halo.skin: must be >= 0, got -1"},
    {"zero_cell", withBase("interest:\n  cell_size: 0\n"),
     "6: interest.cell_size: must be > 0, got 0"},
    {"too_many_cells", withBase("interest: {cell_size: 0.1}\n"),
     "5: interest.cell_size: gives 1000000 cells, more than 65536 (each cell is a DDS partition)"},
    {"halo_wider_than_zone", withBase("halo: {width: 60}\n"),
     "5: halo.width: 60 m is wider than a zone (50 m x 50 m)"},
    {"default_halo_wider_than_zone",
     "world: {min: [0, 0, 0], max: [100, 10, 100]}\ntick: {dt: 0.05}\nseed: 1\n"
     "zones: {columns: 20, rows: 1}\n",
     "1: halo.width: 10 m is wider than a zone (5 m x 100 m)"},
    {"zero_keyframe", withBase("interest:\n  keyframe_every: 0\n"),
     "6: interest.keyframe_every: must be >= 1, got 0"},
    {"duplicate_key", withBase("seed: 2\n"), "5: seed: duplicate key (first given on line 3)"},
    {"unknown_integrator", withBase("physics:\n  integrator: rk5\n"),
     "6: physics.integrator: unknown value 'rk5' (allowed: explicit_euler, semi_implicit_euler, "
     "position_verlet, velocity_verlet, rk2_midpoint, rk4)"},
    {"sleep_not_bool", withBase("physics:\n  sleep: maybe\n"),
     "6: physics.sleep: expected true or false, got 'maybe'"},
    {"negative_linear_drag", withBase("physics:\n  linear_drag: -0.5\n"),
     "6: physics.linear_drag: must be >= 0, got -0.5"},
    {"negative_quadratic_drag", withBase("physics:\n  quadratic_drag: -2\n"),
     "6: physics.quadratic_drag: must be >= 0, got -2"},
    {"compound_without_parts",
     withBase("physics:\n  bodies:\n    - {name: c, shape: compound, position: [5, 1, 5]}\n"),
     "7: physics.bodies[0].parts: required field is missing"},
    {"compound_empty_parts",
     withBase("physics:\n  bodies:\n    - {name: c, shape: compound, position: [5, 1, 5], "
              "parts: []}\n"),
     "7: physics.bodies[0].parts: a compound needs at least one part"},
    {"compound_with_radius",
     withBase("physics:\n  bodies:\n    - {name: c, shape: compound, position: [5, 1, 5], "
              "radius: 2, parts: [{shape: sphere}]}\n"),
     "7: physics.bodies[0].radius: a compound is sized by its parts"},
    {"parts_on_box",
     withBase("physics:\n  bodies:\n    - {name: c, shape: box, position: [5, 1, 5], "
              "parts: [{shape: sphere}]}\n"),
     "7: physics.bodies[0].parts: only compound bodies have parts"},
    {"compound_part_plane",
     withBase("physics:\n  bodies:\n    - name: c\n      shape: compound\n      position: "
              "[5, 1, 5]\n      parts:\n        - {shape: sphere, radius: 1}\n        - "
              "{shape: plane}\n"),
     "12: physics.bodies[0].parts[1].shape: unknown value 'plane' (allowed: sphere, box, capsule)"},
    {"compound_part_size_on_capsule",
     withBase("physics:\n  bodies:\n    - name: c\n      shape: compound\n      position: "
              "[5, 1, 5]\n      parts:\n        - {shape: capsule, size: [1, 1, 1]}\n"),
     "11: physics.bodies[0].parts[0].size: only boxes have a size"},
    {"gyroscopic_not_bool", withBase("physics:\n  gyroscopic: sometimes\n"),
     "6: physics.gyroscopic: expected true or false, got 'sometimes'"},
    {"crowded_cell_wider_than_halo", withBase("lod: {crowded_count: 4, crowded_cell: 20}\n"),
     "5: lod.crowded_cell: 20 m is wider than halo.width (10 m): cells across a border would "
     "count differently per zone"},
    {"joint_hertz_zero", withBase("physics:\n  joint_hertz: 0\n"),
     "6: physics.joint_hertz: must be in [0.1, 10000], got 0"},
    {"collide_with_the_world",
     withBase("physics:\n  bodies:\n    - {name: bob, position: [5, 1, 5]}\n  joints:\n    - "
              "{type: ball, a: bob, anchor: [5, 2, 5], collide: false}\n"),
     "9: physics.joints[0].collide: a joint to the world has no second body to skip"},
    {"size_on_sphere",
     withBase("populations:\n  - kind: rigid_body\n    count: 1\n    size: [1, 1, 1]\n"),
     "8: populations[0].size: only boxes have a size"},
    {"unknown_top_level", withBase("colour: red\n"),
     "5: colour: unknown key (allowed: name, world, tick, seed, zones, interest, halo, "
     "dead_reckoning, physics, populations, clients, map, agents, lod, time_dilation, "
     "interactions, adaptation, gpu)"},
    {"hit_reach_past_halo", withBase("interactions: {hit_reach: 12}\n"),
     "5: interactions.hit_reach: 12 m is beyond halo.width (10 m): targets across a zone border "
     "would not be seen"},
    {"gift_reach_past_halo", withBase("halo: {width: 2}\ninteractions:\n  gift_reach: 3\n"),
     "7: interactions.gift_reach: 3 m is beyond halo.width (2 m): targets across a zone border "
     "would not be seen"},
    {"hit_damage_over_health", withBase("interactions: {hit_damage: 150}\n"),
     "5: interactions.hit_damage: must be in [0, 100], got 150"},
    {"hit_never", withBase("interactions: {hit_every_s: 0}\n"),
     "5: interactions.hit_every_s: must be > 0, got 0"},
    {"interactions_unknown_key", withBase("interactions: {heal: 5}\n"),
     "5: interactions.heal: unknown key (allowed: enabled, hit_reach, hit_every_s, hit_damage, "
     "knockback, gift_reach, gift_every_s, items_per_avatar, items, pickup_reach)"},
    {"item_outside_world", withBase("interactions:\n  items: [[10, 10], [150, 5]]\n"),
     "6: interactions.items[1]: (150, 5) is outside the world"},
    {"item_not_a_point", withBase("interactions:\n  items: [[10, 10, 3]]\n"),
     "6: interactions.items[0]: expected a point [x, z]"},
    {"agent_unknown_action",
     withBase("agents:\n  types:\n    - {name: a, behaviour: tree, tree: dance}\n"),
     "7: agents.types[0].tree: unknown action 'dance' (allowed: idle, wander, chase, flee, "
     "attack, travel)"},
    {"agent_sight_past_halo",
     withBase("agents:\n  types:\n    - {name: a, behaviour: guard, sight: 20}\n"),
     "7: agents.types[0].sight: 20 m is wider than halo.width (10 m)"},
    {"agent_unknown_type",
     withBase("agents:\n  types: [{name: a, behaviour: guard}]\n  populations: [{type: b, "
              "count: 1}]\n"),
     "7: agents.populations[0].type: unknown agent type 'b'"},
    {"agent_navigate_without_map",
     withBase("agents:\n  types:\n    - {name: a, behaviour: travel, goals: [[1, 1]], "
              "navigate: true}\n"),
     "7: agents.types[0].navigate: paths need the scene's map (top-level map: key)"},
    {"agent_unknown_fact",
     withBase("agents:\n  types:\n    - name: a\n      behaviour: goap\n      goap:\n"
              "        facts: [x]\n        goal: {y: true}\n"),
     "11: agents.types[0].goap.goal.y: unknown fact 'y'"},
    {"empty_value", withBase("clients:\n  players:\n  speed: 3\n"),
     "6: clients.players: expected a whole number, got nothing"},
    {"fractional_count", withBase("clients: {players: 2.5}\n"),
     "5: clients.players: expected a whole number, got '2.5'"},
    {"huge_count", withBase("clients: {players: 99999999999}\n"),
     "5: clients.players: is too large, got 99999999999"},
    {"not_finite", withBase("dead_reckoning: {heartbeat_s: .nan}\n"),
     "5: dead_reckoning.heartbeat_s: expected a finite number, got '.nan'"},
    {"overflow", withBase("dead_reckoning: {position_threshold: 1e999}\n"),
     "5: dead_reckoning.position_threshold: expected a finite number, got '1e999'"},
    {"negative_budget", withBase("clients: {downlink_kbps: -20}\n"),
     "5: clients.downlink_kbps: must be >= 0, got -20"},
    {"section_not_mapping", withBase("clients: 4\n"), "5: clients: expected a mapping, got '4'"},
    {"populations_not_list", withBase("populations: {kind: npc}\n"),
     "5: populations: expected a list, got a mapping"},
    {"population_not_mapping", withBase("populations:\n  - npc\n"),
     "6: populations[0]: expected a mapping, got 'npc'"},
    {"missing_kind", withBase("populations:\n  - count: 5\n"),
     "6: populations[0].kind: required field is missing"},
    {"missing_count", withBase("populations:\n  - kind: npc\n    speed: [1, 2]\n"),
     "6: populations[0].count: required field is missing"},
    {"key_of_other_kind", withBase("populations:\n  - kind: npc\n    count: 1\n    rate: 5\n"),
     "8: populations[0].rate: unknown key (allowed: kind, count, speed, acceleration, "
     "waypoint_radius, arrive_distance, region, separation, gather, flock, flow, formation, "
     "colony, roads)"},
    {"gather_outside_world",
     withBase("populations:\n  - kind: npc\n    count: 1\n    gather:\n      point: [500, 0, 5]\n"),
     "9: populations[0].gather.point: is outside the world"},
    {"flock_beyond_halo",
     withBase("halo:\n  width: 2\npopulations:\n  - kind: npc\n    count: 1\n    flock:\n"
              "      radius: 3\n"),
     "11: populations[0].flock.radius: 3 m is wider than halo.width (2 m)"},
    {"flock_and_separation",
     withBase("populations:\n  - kind: npc\n    count: 1\n    separation: {radius: 1}\n"
              "    flock: {radius: 3}\n"),
     "8: populations[0].separation: a flocking population separates through flock.separation"},
    {"flock_and_gather",
     withBase("populations:\n  - kind: npc\n    count: 1\n    gather: {point: [5, 0, 5]}\n"
              "    flock: {radius: 3}\n"),
     "8: populations[0].gather: a flocking population follows its flock, not waypoints"},
    {"flock_separation_beyond_radius",
     withBase("halo:\n  width: 5\npopulations:\n  - kind: npc\n    count: 1\n    flock:\n"
              "      radius: 2\n      separation: {radius: 2.5}\n"),
     "12: populations[0].flock.separation.radius: 2.5 m is wider than flock.radius: neighbours "
     "beyond it are not seen"},
    {"separation_beyond_halo",
     withBase("halo:\n  width: 2\npopulations:\n  - kind: npc\n    count: 1\n    separation:\n"
              "      radius: 3\n"),
     "11: populations[0].separation.radius: 3 m is wider than halo.width (2 m)"},
    {"speed_scalar", withBase("populations:\n  - {kind: npc, count: 1, speed: 2}\n"),
     "6: populations[0].speed: expected a list [min, max], got '2'"},
    {"speed_element",
     withBase("populations:\n  - kind: npc\n    count: 1\n    speed: [1,\n      x]\n"),
     "9: populations[0].speed[1]: expected a finite number, got 'x'"},
    {"negative_speed", withBase("populations:\n  - {kind: npc, count: 1, speed: [-1, 2]}\n"),
     "6: populations[0].speed[0]: must be >= 0, got -1"},
    {"restitution",
     withBase("populations:\n  - kind: rigid_body\n    count: 1\n    restitution: 1.5\n"),
     "8: populations[0].restitution: must be in [0, 1], got 1.5"},
    {"drop_too_high",
     withBase("populations:\n  - {kind: rigid_body, count: 1, drop_height: [5, 12]}\n"),
     "6: populations[0].drop_height: bodies of radius 0.5 dropped from 12 m stick out of the world "
     "(10 m high)"},
    {"default_drop_too_high",
     "world: {min: [0, 0, 0], max: [100, 5, 100]}\n"
     "tick: {dt: 0.05}\nseed: 1\nzones: {columns: 1, rows: 1}\n"
     "populations:\n  - kind: rigid_body\n    count: 1\n",
     "6: populations[0].drop_height: bodies of radius 0.5 dropped from 10 m stick out of the world "
     "(5 m high)"},
    {"region_inverted",
     withBase("populations:\n  - kind: npc\n    count: 1\n    region: {min: [50, 0, 50], max: [40, "
              "0, 60]}\n"),
     "8: populations[0].region.max: x 40 is below region.min 50"},
    {"region_missing_max",
     withBase("populations:\n  - kind: npc\n    count: 1\n    region:\n      min: [1, 0, 1]\n"),
     "9: populations[0].region.max: required field is missing"},
    {"zero_columns",
     "world: {min: [0, 0, 0], max: [100, 10, 100]}\ntick: {dt: 0.05}\nseed: 1\nzones:\n  columns: "
     "0\n  rows: 1\n",
     "5: zones.columns: must be in [1, 256], got 0"},
    {"unknown_layout",
     "world: {min: [0, 0, 0], max: [100, 10, 100]}\ntick: {dt: 0.05}\nseed: 1\n"
     "zones: {layout: hex, columns: 1, rows: 1}\n",
     "4: zones.layout: unknown layout 'hex' (allowed: grid, rcb)"},
    {"negative_seed",
     "world: {min: [0, 0, 0], max: [100, 10, 100]}\ntick: {dt: 0.05}\nseed: -1\nzones: {columns: "
     "1, rows: 1}\n",
     "3: seed: must be >= 0, got -1"},
    {"short_vector", "world:\n  min: [0, 0]\n  max: [1, 1, 1]\n",
     "2: world.min: expected a list [x, y, z], got a list of 2 items"},
    {"missing_world", "\n# nothing yet\ntick: {dt: 0.05}\nseed: 1\nzones: {columns: 1, rows: 1}\n",
     "3: world: required field is missing"},
    {"empty_name", withBase("name: ''\n"), "5: name: must not be empty"},
    {"empty_file", "# only a comment\n",
     "1: document: the file is empty; expected world, tick, seed and zones"},
    {"top_level_list", "- 1\n- 2\n", "1: document: expected a mapping, got a list of 2 items"},
    {"two_documents", withBase("---\nseed: 2\n"),
     "5: document: a scene file holds one YAML document, found more"},
    {"stray_comma", "# a comment\n, world: {}\n",
     "2: yaml: unexpected token (a ',' outside [ ] or { }?)"},
    {"stray_comma_after_list", "[1, 2]\n, 3\n",
     "2: yaml: unexpected token (a ',' outside [ ] or { }?)"},
    {"syntax", "world:\n  min: [0, 0, 0]\n   max: [1, 1, 1]\n", "3: yaml: end of map not found"},
    {"kind_unknown", withBase("clients:\n  kinds:\n    plane: {speed: 30, share: 1}\n"),
     "7: clients.kinds.plane: unknown kind 'plane' (allowed: walker, rider, flyer)"},
    {"kind_negative_speed", withBase("clients:\n  kinds:\n    walker: {speed: -1, share: 1}\n"),
     "7: clients.kinds.walker.speed: must be >= 0, got -1"},
    {"kind_zero_nimbus", withBase("clients:\n  kinds:\n    rider: {nimbus: 0, share: 1}\n"),
     "7: clients.kinds.rider.nimbus: must be > 0, got 0"},
    {"kind_without_share", withBase("clients:\n  kinds:\n    walker: {speed: 3}\n"),
     "7: clients.kinds.walker.share: required field is missing"},
    {"kind_shares_short",
     withBase("clients:\n  kinds:\n    walker: {share: 0.7}\n    rider: {share: 0.2}\n"),
     "7: clients.kinds: shares sum to 0.9, not 1"},
    {"kind_none", withBase("clients:\n  kinds: {}\n"),
     "6: clients.kinds: lists no kind (allowed: walker, rider, flyer)"},
    {"kind_flyer_above_world",
     withBase("clients:\n  kinds:\n    flyer: {speed: 30, height: 80, share: 1}\n"),
     "7: clients.kinds.flyer.height: 80 m above the ground is outside the world (y in [0, 10])"},
    {"kind_flyer_without_height", withBase("clients:\n  kinds:\n    flyer: {share: 1}\n"),
     "7: clients.kinds.flyer.height: required field is missing"},
    {"kind_walker_with_height", withBase("clients:\n  kinds:\n    walker: {height: 2, share: 1}\n"),
     "7: clients.kinds.walker.height: only flyers have a height"},
    {"kind_duplicate",
     withBase("clients:\n  kinds:\n    walker: {share: 0.5}\n    walker: {share: 0.5}\n"),
     "8: clients.kinds.walker: duplicate key (first given on line 7)"},
};

class InlineBadScene : public ::testing::TestWithParam<InlineCase> {};

TEST_P(InlineBadScene, FailsWithFileLineAndField) {
  const InlineCase& c = GetParam();
  EXPECT_EQ(sceneError([&] { parseScene(c.text, "inline.yaml"); }), "inline.yaml:" + c.message);
}

INSTANTIATE_TEST_SUITE_P(Texts, InlineBadScene, ::testing::ValuesIn(kInlineCases),
                         [](const auto& info) { return std::string(info.param.label); });

TEST(SceneErrors, BaseTextOfTheInlineCasesIsValid) {
  Scene s = parseScene(kBase, "inline.yaml");
  EXPECT_EQ(s.zones.columns, 2);
}

}  // namespace
}  // namespace zonesim
