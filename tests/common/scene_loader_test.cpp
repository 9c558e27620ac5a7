// Scene files that should load: the shipped scenes, the demo's values, and the defaults
// that fill in optional keys.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "common/scene.h"
#include "scene_test_util.h"

namespace zonesim {
namespace {

using test::sceneError;
using test::sourcePath;

std::vector<std::string> shippedScenes() {
  return test::yamlStems("scenes");
}

class ShippedScene : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedScene, LoadsWithItsNameAndPath) {
  std::string path = sourcePath("scenes/" + GetParam() + ".yaml");
  Scene scene = loadScene(path);
  EXPECT_EQ(scene.name, GetParam());
  EXPECT_EQ(scene.source_path, path);
  EXPECT_GT(scene.npcs.size() + scene.rigid_bodies.size() + scene.emitters.size() +
                scene.agents.populations.size() + scene.physics.bodies.size(),
            0u);
}

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedScene, ::testing::ValuesIn(shippedScenes()),
                         [](const auto& info) { return info.param; });

TEST(ShippedScenes, IncludeTheOnesOtherTestsUse) {
  std::vector<std::string> names = shippedScenes();
  for (const char* wanted : {"demo", "test_small", "test_npc_only", "test_single_zone"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), wanted), names.end()) << wanted;
  }
}

TEST(DemoScene, ValuesComeThrough) {
  Scene s = loadScene(sourcePath("scenes/demo.yaml"));
  EXPECT_DOUBLE_EQ(s.world.max.x - s.world.min.x, 400);
  EXPECT_DOUBLE_EQ(s.world.max.z - s.world.min.z, 400);
  EXPECT_DOUBLE_EQ(s.world.min.y, 0);
  EXPECT_DOUBLE_EQ(s.world.max.y, 100);
  EXPECT_EQ(s.dt, 1.0 / 30);
  EXPECT_DOUBLE_EQ(s.tick_rate, 30);
  EXPECT_EQ(s.zones.kind, SceneZones::Kind::Grid);
  EXPECT_EQ(s.zones.columns, 2);
  EXPECT_EQ(s.zones.rows, 2);
  EXPECT_DOUBLE_EQ(s.interest_cell_size, 50);
  EXPECT_DOUBLE_EQ(s.halo_width, 10);
  EXPECT_FALSE(s.halo_skin.has_value());
  EXPECT_DOUBLE_EQ(haloSkin(s), 2);  // width / 5

  ASSERT_EQ(s.npcs.size(), 1u);
  EXPECT_EQ(s.npcs[0].count, 4000);
  EXPECT_DOUBLE_EQ(s.npcs[0].min_speed, 1.0);
  EXPECT_DOUBLE_EQ(s.npcs[0].max_speed, 2.5);
  EXPECT_DOUBLE_EQ(s.npcs[0].waypoint_radius, 60);
  EXPECT_DOUBLE_EQ(s.npcs[0].region.max.x, 400);

  ASSERT_EQ(s.rigid_bodies.size(), 3u);
  EXPECT_EQ(s.rigid_bodies[0].count, 40);
  EXPECT_EQ(s.rigid_bodies[0].shape, RigidBodyPopulation::Shape::Sphere);
  EXPECT_DOUBLE_EQ(s.rigid_bodies[0].drop_height, 10);
  EXPECT_DOUBLE_EQ(s.rigid_bodies[0].max_drop_height, 20);
  EXPECT_EQ(s.rigid_bodies[1].shape, RigidBodyPopulation::Shape::Box);
  EXPECT_DOUBLE_EQ(s.rigid_bodies[1].size.y, 0.5);
  EXPECT_DOUBLE_EQ(s.rigid_bodies[1].friction, 0.6);
  EXPECT_EQ(s.rigid_bodies[2].shape, RigidBodyPopulation::Shape::Capsule);
  EXPECT_DOUBLE_EQ(s.rigid_bodies[2].length, 1.2);
  EXPECT_EQ(s.physics.integrator, PhysicsSettings::Integrator::SemiImplicitEuler);
  EXPECT_TRUE(s.physics.sleep);

  ASSERT_EQ(s.emitters.size(), 1u);
  EXPECT_EQ(s.emitters[0].count, 4);
  EXPECT_DOUBLE_EQ(s.emitters[0].rate, 200);
  EXPECT_DOUBLE_EQ(s.emitters[0].lifetime, 2);

  EXPECT_EQ(s.clients.players, 32);
  EXPECT_DOUBLE_EQ(s.clients.speed, 6);
  EXPECT_DOUBLE_EQ(s.clients.input_hz, 20);
  EXPECT_DOUBLE_EQ(s.clients.nimbus, 60);
}

TEST(TestScenes, HaveTheShapeTheirNamesPromise) {
  Scene small = loadScene(sourcePath("scenes/test_small.yaml"));
  EXPECT_EQ(small.zones.columns * small.zones.rows, 4);
  ASSERT_EQ(small.npcs.size(), 1u);
  EXPECT_EQ(small.npcs[0].count, 200);
  EXPECT_EQ(small.emitters.size(), 1u);

  Scene npc_only = loadScene(sourcePath("scenes/test_npc_only.yaml"));
  EXPECT_FALSE(npc_only.npcs.empty());
  EXPECT_TRUE(npc_only.rigid_bodies.empty());
  EXPECT_TRUE(npc_only.emitters.empty());

  Scene single = loadScene(sourcePath("scenes/test_single_zone.yaml"));
  EXPECT_EQ(single.zones.columns, 1);
  EXPECT_EQ(single.zones.rows, 1);
}

constexpr const char* kMinimal =
    "world: {min: [-10, 0, -20], max: [90, 20, 80]}\n"
    "tick: {dt: 0.025}\n"
    "seed: 18446744073709551615\n"
    "zones: {columns: 3, rows: 1}\n";

TEST(SceneDefaults, AppliedWhenOptionalKeysAreAbsent) {
  Scene s = parseScene(kMinimal, "dir/minimal.scene.yaml");
  EXPECT_EQ(s.name, "minimal.scene");
  EXPECT_EQ(s.source_path, "");
  EXPECT_EQ(s.seed, 18446744073709551615ULL);
  EXPECT_DOUBLE_EQ(s.tick_rate, 40);  // real time: 1 / dt
  EXPECT_DOUBLE_EQ(s.world.min.z, -20);
  EXPECT_EQ(s.zones.columns, 3);
  Scene plain;
  EXPECT_DOUBLE_EQ(s.interest_cell_size, plain.interest_cell_size);
  EXPECT_EQ(s.keyframe_every, plain.keyframe_every);
  EXPECT_DOUBLE_EQ(s.halo_width, plain.halo_width);
  EXPECT_DOUBLE_EQ(s.dead_reckoning.position_threshold, plain.dead_reckoning.position_threshold);
  EXPECT_DOUBLE_EQ(s.dead_reckoning.heartbeat_seconds, plain.dead_reckoning.heartbeat_seconds);
  EXPECT_EQ(s.clients.players, plain.clients.players);
  EXPECT_DOUBLE_EQ(s.clients.nimbus, plain.clients.nimbus);
  EXPECT_DOUBLE_EQ(s.clients.retarget_seconds, plain.clients.retarget_seconds);
  EXPECT_TRUE(s.npcs.empty());
  EXPECT_TRUE(s.rigid_bodies.empty());
  EXPECT_TRUE(s.emitters.empty());
}

TEST(SceneDefaults, PopulationsTakeTheirDefaultsAndTheWorldAsRegion) {
  Scene s = parseScene(std::string(kMinimal) +
                           "populations:\n"
                           "  - {kind: npc, count: 3}\n"
                           "  - {kind: rigid_body, count: 2}\n"
                           "  - {kind: particle_emitter, count: 1}\n"
                           "  - {kind: npc, count: 0, speed: [0, 0]}\n",
                       "pops");
  ASSERT_EQ(s.npcs.size(), 2u);
  ASSERT_EQ(s.rigid_bodies.size(), 1u);
  ASSERT_EQ(s.emitters.size(), 1u);
  NpcPopulation npc;
  EXPECT_DOUBLE_EQ(s.npcs[0].min_speed, npc.min_speed);
  EXPECT_DOUBLE_EQ(s.npcs[0].max_speed, npc.max_speed);
  EXPECT_DOUBLE_EQ(s.npcs[0].waypoint_radius, npc.waypoint_radius);
  EXPECT_DOUBLE_EQ(s.npcs[0].region.min.x, -10);
  EXPECT_DOUBLE_EQ(s.npcs[0].region.max.z, 80);
  EXPECT_EQ(s.npcs[1].count, 0);
  EXPECT_DOUBLE_EQ(s.npcs[1].max_speed, 0);
  RigidBodyPopulation body;
  EXPECT_DOUBLE_EQ(s.rigid_bodies[0].radius, body.radius);
  EXPECT_DOUBLE_EQ(s.rigid_bodies[0].drop_height, body.drop_height);
  EXPECT_DOUBLE_EQ(s.rigid_bodies[0].max_drop_height, body.max_drop_height);
  EXPECT_DOUBLE_EQ(s.rigid_bodies[0].region.max.y, 20);
  EmitterPopulation emitter;
  EXPECT_DOUBLE_EQ(s.emitters[0].rate, emitter.rate);
  EXPECT_EQ(s.emitters[0].max_particles, emitter.max_particles);
}

TEST(SceneDefaults, ExplicitValuesOverrideThem) {
  Scene s = parseScene(
      "name: custom\n"
      "world: {min: [0, 0, 0], max: [10, 10, 10]}\n"
      "tick: {dt: 0.025, rate_hz: 10}\n"
      "seed: 5\n"
      "zones: {layout: grid, columns: 1, rows: 1}\n"
      "interest: {cell_size: 2.5, keyframe_every: 1}\n"
      "halo: {width: 0, skin: 0.25}\n"
      "dead_reckoning: {position_threshold: 0, heartbeat_s: 0.5}\n"
      "clients: {players: 0, speed: 0, input_hz: 1, nimbus: 4, retarget_s: 2, downlink_kbps: 20,\n"
      "          downlink_error_angle_deg: 1}\n",
      "x");
  EXPECT_EQ(s.name, "custom");
  EXPECT_DOUBLE_EQ(s.tick_rate, 10);
  EXPECT_DOUBLE_EQ(s.interest_cell_size, 2.5);
  EXPECT_EQ(s.keyframe_every, 1);
  EXPECT_DOUBLE_EQ(s.halo_width, 0);
  EXPECT_DOUBLE_EQ(haloSkin(s), 0.25);
  EXPECT_DOUBLE_EQ(s.dead_reckoning.position_threshold, 0);
  EXPECT_DOUBLE_EQ(s.dead_reckoning.heartbeat_seconds, 0.5);
  EXPECT_EQ(s.clients.players, 0);
  EXPECT_DOUBLE_EQ(s.clients.input_hz, 1);
  EXPECT_DOUBLE_EQ(s.clients.nimbus, 4);
  EXPECT_DOUBLE_EQ(s.clients.retarget_seconds, 2);
  EXPECT_DOUBLE_EQ(s.clients.downlink_kbps, 20);
  EXPECT_DOUBLE_EQ(s.clients.downlink_error_angle_deg, 1);
}

TEST(SceneDefaults, InteractionsOffWithoutTheKeyAndOnWithIt) {
  EXPECT_FALSE(parseScene(kMinimal, "x").interactions.enabled);
  Scene s = parseScene(std::string(kMinimal) +
                           "interactions: {hit_reach: 2, hit_every_s: 0.5, hit_damage: 40,\n"
                           "               knockback: 0, gift_reach: 3, gift_every_s: 1.5,\n"
                           "               items_per_avatar: 4, pickup_reach: 2,\n"
                           "               items: [[1, 2], [30, -5]]}\n",
                       "x");
  const InteractionSettings& in = s.interactions;
  EXPECT_TRUE(in.enabled);
  EXPECT_DOUBLE_EQ(in.hit_reach, 2);
  EXPECT_DOUBLE_EQ(in.hit_every_s, 0.5);
  EXPECT_EQ(in.hit_damage, 40);
  EXPECT_DOUBLE_EQ(in.knockback, 0);
  EXPECT_DOUBLE_EQ(in.gift_reach, 3);
  EXPECT_DOUBLE_EQ(in.gift_every_s, 1.5);
  EXPECT_EQ(in.items_per_avatar, 4);
  EXPECT_DOUBLE_EQ(in.pickup_reach, 2);
  ASSERT_EQ(in.items.size(), 2u);
  EXPECT_DOUBLE_EQ(in.items[1][0], 30);
  EXPECT_DOUBLE_EQ(in.items[1][1], -5);
  EXPECT_FALSE(parseScene(std::string(kMinimal) + "interactions: {enabled: false}\n", "x")
                   .interactions.enabled);
}

TEST(SceneDefaults, DeadReckoningModelsAndQuantisation) {
  Scene plain = parseScene(kMinimal, "x");
  EXPECT_EQ(plain.dead_reckoning.npc.order, DeadReckoningModel::Order::First);
  EXPECT_EQ(plain.dead_reckoning.rigid_body.order, DeadReckoningModel::Order::Second);
  EXPECT_TRUE(plain.dead_reckoning.rigid_body.rotating);
  EXPECT_EQ(plain.dead_reckoning.emitter.order, DeadReckoningModel::Order::Static);
  EXPECT_DOUBLE_EQ(plain.dead_reckoning.orientation_threshold_deg, 3);
  Scene s = parseScene(
      std::string(kMinimal) +
          "dead_reckoning:\n"
          "  orientation_threshold_deg: 5\n"
          "  models: {npc: {order: second, orientation: rotating}, avatar: {order: static}}\n"
          "  quantisation: {position_resolution: 0.01, rotation_bits: 12}\n",
      "x");
  EXPECT_EQ(s.dead_reckoning.npc.order, DeadReckoningModel::Order::Second);
  EXPECT_TRUE(s.dead_reckoning.npc.rotating);
  EXPECT_EQ(s.dead_reckoning.avatar.order, DeadReckoningModel::Order::Static);
  EXPECT_FALSE(s.dead_reckoning.avatar.rotating);
  EXPECT_DOUBLE_EQ(s.dead_reckoning.orientation_threshold_deg, 5);
  EXPECT_DOUBLE_EQ(s.dead_reckoning.quantisation.position_resolution, 0.01);
  EXPECT_EQ(s.dead_reckoning.quantisation.rotation_bits, 12);
  EXPECT_THROW(
      parseScene(std::string(kMinimal) + "dead_reckoning: {models: {npc: {order: third}}}\n", "x"),
      SceneError);
}

TEST(SceneDefaults, AurasAndNimbusGrowth) {
  Scene plain = parseScene(kMinimal, "x");
  EXPECT_DOUBLE_EQ(plain.aura_nimbus.npc, 100);
  EXPECT_DOUBLE_EQ(plain.aura_nimbus.max_nimbus, 150);
  Scene s = parseScene(std::string(kMinimal) +
                           "interest: {aura: {npc: 30, particle_emitter: 400}, "
                           "nimbus_per_speed: 2, max_nimbus: 90}\n",
                       "x");
  EXPECT_DOUBLE_EQ(s.aura_nimbus.npc, 30);
  EXPECT_DOUBLE_EQ(s.aura_nimbus.emitter, 400);
  EXPECT_DOUBLE_EQ(s.aura_nimbus.avatar, 150);
  EXPECT_DOUBLE_EQ(s.aura_nimbus.nimbus_per_speed, 2);
  EXPECT_DOUBLE_EQ(s.aura_nimbus.max_nimbus, 90);
  EXPECT_THROW(parseScene(std::string(kMinimal) + "interest: {aura: {npc: 0}}\n", "x"), SceneError);
}

TEST(SceneDefaults, OneImplicitWalkerWithoutKinds) {
  Scene s = parseScene(std::string(kMinimal) + "clients: {speed: 4, nimbus: 70}\n", "x");
  EXPECT_TRUE(s.clients.kinds.empty());
  std::vector<PlayerKind> kinds = playerKinds(s.clients);
  ASSERT_EQ(kinds.size(), 1u);
  EXPECT_EQ(kinds[0].id, PlayerKindId::Walker);
  EXPECT_DOUBLE_EQ(kinds[0].speed, 4);
  EXPECT_DOUBLE_EQ(kinds[0].nimbus, 70);
  EXPECT_DOUBLE_EQ(kinds[0].height, 0);
  EXPECT_DOUBLE_EQ(kinds[0].share, 1);
  EXPECT_TRUE(playerKind(s.clients, 0).has_value());
  EXPECT_FALSE(playerKind(s.clients, 2).has_value()) << "no flyers in a scene without kinds";
}

TEST(SceneKinds, ListedInIdOrderWithTheClientsDefaults) {
  Scene s = parseScene(std::string(kMinimal) +
                           "clients:\n"
                           "  speed: 4\n"
                           "  nimbus: 70\n"
                           "  kinds:\n"
                           "    flyer: {speed: 30, nimbus: 300, height: 15, share: 0.1}\n"
                           "    walker: {share: 0.7}\n"
                           "    rider: {speed: 12, nimbus: 150, share: 0.2}\n",
                       "x");
  const std::vector<PlayerKind>& k = s.clients.kinds;
  ASSERT_EQ(k.size(), 3u);
  EXPECT_EQ(k[0].id, PlayerKindId::Walker);
  EXPECT_DOUBLE_EQ(k[0].speed, 4);  // clients.speed and clients.nimbus unless given
  EXPECT_DOUBLE_EQ(k[0].nimbus, 70);
  EXPECT_DOUBLE_EQ(k[0].share, 0.7);
  EXPECT_EQ(k[1].id, PlayerKindId::Rider);
  EXPECT_DOUBLE_EQ(k[1].speed, 12);
  EXPECT_DOUBLE_EQ(k[1].nimbus, 150);
  EXPECT_DOUBLE_EQ(k[1].height, 0);
  EXPECT_EQ(k[2].id, PlayerKindId::Flyer);
  EXPECT_DOUBLE_EQ(k[2].speed, 30);
  EXPECT_DOUBLE_EQ(k[2].nimbus, 300);
  EXPECT_DOUBLE_EQ(k[2].height, 15);
  EXPECT_DOUBLE_EQ(k[2].share, 0.1);
  EXPECT_EQ(playerKinds(s.clients).size(), 3u);
  EXPECT_DOUBLE_EQ(playerKind(s.clients, 2)->nimbus, 300);
  EXPECT_FALSE(playerKind(s.clients, 3).has_value());
  // A subset: a scene of riders only has no walker to fall back on.
  Scene riders =
      parseScene(std::string(kMinimal) + "clients: {kinds: {rider: {speed: 9, share: 1}}}\n", "x");
  EXPECT_FALSE(playerKind(riders.clients, 0).has_value());
  EXPECT_DOUBLE_EQ(playerKind(riders.clients, 1)->speed, 9);
}

TEST(CompoundsScene, PartsAndTheGyroscopicSwitchComeThrough) {
  Scene s = loadScene(sourcePath("scenes/compounds.yaml"));
  EXPECT_TRUE(s.physics.gyroscopic);
  const SceneBody& table = s.physics.bodies[0];
  EXPECT_EQ(table.shape, SceneBody::Shape::Compound);
  ASSERT_EQ(table.parts.size(), 5u);
  EXPECT_EQ(table.parts[0].shape, SceneBody::Shape::Box);
  EXPECT_DOUBLE_EQ(table.parts[0].size.y, 0.1);
  EXPECT_DOUBLE_EQ(table.parts[0].position.y, 0.85);
  EXPECT_DOUBLE_EQ(table.parts[4].position.z, 0.45);
  const SceneBody& hammer = s.physics.bodies[3];
  ASSERT_EQ(hammer.parts.size(), 2u);
  EXPECT_EQ(hammer.parts[0].shape, SceneBody::Shape::Capsule);
  EXPECT_DOUBLE_EQ(hammer.parts[0].length, 0.8);
  EXPECT_EQ(s.physics.bodies[4].motion, SceneBody::Motion::Static);
  EXPECT_TRUE(s.physics.bodies[5].parts.empty());  // the ball: a plain sphere
}

TEST(PlayerKindNames, EachIdHasOneName) {
  for (std::size_t i = 0; i < kPlayerKindCount; ++i)
    EXPECT_EQ(playerKindNamed(playerKindName(std::uint8_t(i))), PlayerKindId(i));
  EXPECT_EQ(playerKindName(std::uint8_t(7)), "unknown");
  EXPECT_FALSE(playerKindNamed("plane").has_value());
}

TEST(SceneFormatDoc, CompleteExampleLoads) {
  std::ifstream in(sourcePath("docs/scene-format.md"));
  std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t start = doc.find("```yaml\n", doc.find("## A complete example"));
  ASSERT_NE(start, std::string::npos);
  start += 8;
  std::string example = doc.substr(start, doc.find("```", start) - start);
  Scene s = parseScene(example, "scene-format.md");
  EXPECT_EQ(s.name, "plaza");
  EXPECT_EQ(s.npcs.size() + s.rigid_bodies.size() + s.emitters.size(), 3u);
  EXPECT_DOUBLE_EQ(s.tick_rate, 60);
}

TEST(LoadScene, MissingFileIsAnError) {
  std::string path = sourcePath("scenes/no_such_scene.yaml");
  EXPECT_EQ(sceneError([&] { loadScene(path); }), path + ":0: file: cannot open");
}

TEST(LoadScene, DirectoryIsAnError) {
  std::string path = sourcePath("scenes");
  EXPECT_EQ(sceneError([&] { loadScene(path); }), path + ":0: file: cannot open");
}

TEST(SceneLoader, ReadsSolverSeparationAndGathering) {
  Scene s = parseScene(R"(world: {min: [0, 0, 0], max: [100, 10, 100]}
tick: {dt: 0.02}
seed: 1
zones: {columns: 2, rows: 1}
halo: {width: 4}
physics: {solver: sor, sor_omega: 1.5}
populations:
  - kind: npc
    count: 3
    separation: {radius: 2, weight: 0.5}
    gather: {point: [20, 0, 30], radius: 5, start_s: 1, end_s: 9}
)",
                       "inline.yaml");
  EXPECT_EQ(s.physics.solver, PhysicsSettings::Solver::Sor);
  EXPECT_DOUBLE_EQ(s.physics.sor_omega, 1.5);
  ASSERT_EQ(s.npcs.size(), 1u);
  EXPECT_DOUBLE_EQ(s.npcs[0].separation_radius, 2);
  EXPECT_DOUBLE_EQ(s.npcs[0].separation_weight, 0.5);
  EXPECT_DOUBLE_EQ(s.npcs[0].gather.x, 20);
  EXPECT_DOUBLE_EQ(s.npcs[0].gather.z, 30);
  EXPECT_DOUBLE_EQ(s.npcs[0].gather.radius, 5);
  EXPECT_DOUBLE_EQ(s.npcs[0].gather.start_s, 1);
  EXPECT_DOUBLE_EQ(s.npcs[0].gather.end_s, 9);
}

// The scenes' default solver is the wide soft step; it gives way to the soft step, which solves
// rolling resistance, only where the scene names no solver and some population rolls.
TEST(SceneLoader, TheDefaultSolverIsTheWideSoftStepUnlessABodyRollsWithResistance) {
  const std::string head =
      "world: {min: [0, 0, 0], max: [100, 20, 100]}\ntick: {dt: 0.02}\nseed: 1\n"
      "zones: {columns: 1, rows: 1}\n";
  const std::string rolling =
      "populations:\n  - {kind: rigid_body, count: 2, rolling_resistance: 0.02}\n";
  Scene plain = parseScene(head + "populations:\n  - {kind: rigid_body, count: 2}\n", "x");
  EXPECT_EQ(plain.physics.solver, PhysicsSettings::Solver::SoftStepWide);
  EXPECT_FALSE(plain.physics.solver_named);
  Scene rolls = parseScene(head + rolling, "x");
  EXPECT_EQ(rolls.physics.solver, PhysicsSettings::Solver::SoftStep);
  Scene named = parseScene(head + "physics: {solver: gauss_seidel}\n" + rolling, "x");
  EXPECT_EQ(named.physics.solver, PhysicsSettings::Solver::GaussSeidel);
  EXPECT_TRUE(named.physics.solver_named);
  EXPECT_EQ(
      sceneError([&] { parseScene(head + "physics: {solver: soft_step_wide}\n" + rolling, "x"); }),
      "x:7: populations[0].rolling_resistance: is not solved by physics.solver "
      "soft_step_wide");
}

TEST(SceneLoader, ReadsJointSpringsAndCollideFlag) {
  Scene s = parseScene(std::string("world: {min: [0, 0, 0], max: [10, 10, 10]}\n"
                                   "tick: {dt: 0.025}\nseed: 1\nzones: {columns: 1, rows: 1}\n") +
                           "physics:\n  solver: soft_step\n  joint_hertz: 120\n"
                           "  joint_damping_ratio: 5\n  bodies:\n"
                           "    - {name: l1, shape: capsule, position: [5, 5, 5]}\n"
                           "    - {name: l2, shape: capsule, position: [5, 4, 5]}\n"
                           "  joints:\n    - {type: ball, a: l1, b: l2, anchor: [5, 4.5, 5], "
                           "collide: false}\n    - {type: ball, a: l1, anchor: [5, 5.5, 5]}\n",
                       "x");
  EXPECT_DOUBLE_EQ(s.physics.joint_hertz, 120);
  EXPECT_DOUBLE_EQ(s.physics.joint_damping_ratio, 5);
  ASSERT_EQ(s.physics.joints.size(), 2u);
  EXPECT_FALSE(s.physics.joints[0].collide);
  EXPECT_TRUE(s.physics.joints[1].collide);  // the default: jointed bodies still touch
}

}  // namespace
}  // namespace zonesim
