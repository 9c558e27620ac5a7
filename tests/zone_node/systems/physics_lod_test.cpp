// Level of detail for a zone's rigid bodies (lod.physics_every): bodies far from every player
// and observer wait for their island's step, near ones step every tick, and a scene without
// the key holds nothing. Counted, not timed.
#include <gtest/gtest.h>

#include <string>

#include "common/scene.h"
#include "zone_node/population.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/systems/rigid_bodies.h"

namespace zonesim::zone {
namespace {

// Boxes tumbling onto the ground near the observer at (5, 5) and far from it (beyond 40 m).
std::string bodiesScene(const std::string& lod) {
  return R"(world: {min: [0, 0, 0], max: [100, 20, 100]}
tick: {dt: 0.05}
seed: 5
zones: {columns: 1, rows: 1}
physics: {sleep: false}
populations:
  - {kind: rigid_body, count: 8, shape: box, size: [1, 1, 1], drop_height: [2, 4],
     region: {min: [2, 0, 2], max: [8, 0, 8]}}
  - {kind: rigid_body, count: 24, shape: box, size: [1, 1, 1], drop_height: [2, 4],
     region: {min: [60, 0, 60], max: [95, 0, 95]}}
)" + lod;
}

struct Counts {
  std::uint64_t held = 0, awake = 0;
};

// Steps `ticks` ticks; sums the held and awake body counts over them.
Counts run(const Scene& scene, int ticks, std::vector<crowd::Vec2> players) {
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  RigidBodySystem bodies(scene, 0);
  LoneZone lone{scene.dt};
  lone.players = std::move(players);
  Counts c;
  for (int t = 0; t < ticks; ++t) {
    const TickCounters& k = lone.step(bodies, store, std::uint64_t(t));
    c.held += k.bodies_held;
    c.awake += k.bodies_awake;
  }
  return c;
}

TEST(PhysicsLod, FarBodiesWaitForTheirStepNearOnesDoNot) {
  const Scene scene = parseScene(
      bodiesScene("lod: {near_radius: 40, physics_every: 4, physics_max_step: 0.2, "
                  "observers: [[5, 0, 5]]}\n"),
      "physics_lod.yaml");
  const int ticks = 40;
  const Counts c = run(scene, ticks, {{5.0, 5.0}});
  // The 24 far boxes are held on 3 ticks of every 4 (none sleeps: sleeping is off); the 8 near
  // ones never.
  EXPECT_EQ(c.awake, 32u * ticks);
  EXPECT_EQ(c.held, 24u * 3 * ticks / 4);
}

TEST(PhysicsLod, WithoutPhysicsEveryNothingIsHeld) {
  const Scene scene =
      parseScene(bodiesScene("lod: {near_radius: 40, observers: [[5, 0, 5]]}\n"), "crowds.yaml");
  EXPECT_EQ(run(scene, 20, {{5.0, 5.0}}).held, 0u);
  const Scene plain = parseScene(bodiesScene(""), "plain.yaml");
  EXPECT_EQ(run(plain, 20, {}).held, 0u);
}

TEST(PhysicsLod, WithNoPlayerEveryBodyIsFar) {
  const Scene scene =
      parseScene(bodiesScene("lod: {physics_every: 2, physics_max_step: 0}\n"), "no_players.yaml");
  const int ticks = 20;
  EXPECT_EQ(run(scene, ticks, {}).held, 32u * ticks / 2);
}

TEST(PhysicsLod, TheLongestStepBinds) {
  // The default longest step, 1/15 s, is shorter than two 0.05 s ticks: every body steps every
  // tick. 0.1 s lets them wait one tick in two.
  const int ticks = 20;
  const Scene tight = parseScene(bodiesScene("lod: {physics_every: 4}\n"), "tight.yaml");
  EXPECT_EQ(run(tight, ticks, {}).held, 0u);
  const Scene loose =
      parseScene(bodiesScene("lod: {physics_every: 4, physics_max_step: 0.1}\n"), "loose.yaml");
  EXPECT_EQ(run(loose, ticks, {}).held, 32u * ticks / 2);
}

}  // namespace
}  // namespace zonesim::zone
