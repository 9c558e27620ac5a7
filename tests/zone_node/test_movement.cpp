#include <gtest/gtest.h>

#include "test_helpers.h"
#include "zone_node/population.h"
#include "zone_node/systems/avatar_movement.h"
#include "zone_node/systems/ground_bodies.h"
#include "zone_node/systems/npc_movement.h"

namespace zonesim::zone {
namespace {

TEST(NpcMovement, NpcsWanderWithinTheWorldAtTheirOwnSpeedAndReachWaypoints) {
  Scene s = testing::npcScene(200);
  EntityStore store;
  forEachInitialEntity(s, [&](const EntityRecordData& r) { store.add(r); });
  std::vector<Vec3> first_waypoint;
  for (const NpcData& n : store.npc) first_waypoint.push_back(n.waypoint);
  double max_speed_seen = 0;
  for (int t = 0; t < 30 * 60; ++t) {
    stepNpcs(s, store, s.dt);
    for (std::size_t i = 0; i < store.size(); ++i) {
      ASSERT_GE(store.pos[i].x(), s.world.min.x - 1e-9);
      ASSERT_LE(store.pos[i].x(), s.world.max.x + 1e-9);
      ASSERT_GE(store.pos[i].z(), s.world.min.z - 1e-9);
      ASSERT_LE(store.pos[i].z(), s.world.max.z + 1e-9);
      double speed = store.vel[i].norm();
      max_speed_seen = std::max(max_speed_seen, speed / store.npc[i].max_speed);
    }
  }
  EXPECT_LE(max_speed_seen, 1.0 + 1e-9);  // steering never overshoots the NPC's top speed
  std::size_t moved_on = 0;
  for (std::size_t i = 0; i < store.size(); ++i)
    moved_on += store.npc[i].waypoint != first_waypoint[i];
  EXPECT_GT(moved_on, store.size() * 9 / 10) << "most NPCs reached their first waypoint in 60 s";
}

TEST(AvatarMovement, AnAvatarWalksInTheInputDirectionAtItsSpeed) {
  EntityStore store;
  EntityRecordData r;
  r.id = EntityId::make(0, 1);
  r.kind = EntityKind::Avatar;
  r.avatar.max_speed = 6;
  r.avatar.move_x = 1;
  store.add(r);
  const SceneBox world{{-100, 0, -100}, {100, 10, 100}};
  for (int t = 0; t < 60; ++t) stepAvatars(world, store, 1.0 / 30);
  EXPECT_NEAR(store.vel[0].x(), 6.0, 1e-9);
  EXPECT_NEAR(store.vel[0].z(), 0.0, 1e-12);
  // 2 s: full speed after 0.25 s of constant acceleration, so 12 m minus 6 * 0.25 / 2 m of ramp.
  EXPECT_NEAR(store.pos[0].x(), 12.0 - 0.75, 0.15);
}

TEST(GroundBodies, ADroppedSphereReboundsToRestitutionSquaredTimesItsHeightAndSleeps) {
  SceneBox world{{0, 0, 0}, {100, 100, 100}};
  EntityStore store;
  EntityRecordData r;
  r.id = EntityId::make(0, 1);
  r.kind = EntityKind::RigidBody;
  r.body.radius = 0.5;
  r.body.restitution = 0.6;
  const double h = 10.0;
  r.pos = Vec3(50, 0.5 + h, 50);
  store.add(r);
  const double dt = 1.0 / 600;
  double apex = 0;
  bool bounced = false;
  for (int t = 0; t < 600 * 4; ++t) {
    stepGroundBodies(world, store, dt);
    if (store.vel[0].y() > 0) bounced = true;
    if (bounced) apex = std::max(apex, store.pos[0].y() - 0.5);
    if (bounced && store.vel[0].y() < 0 && store.pos[0].y() - 0.5 < apex * 0.5) break;
  }
  // Analytic apex after one bounce: e^2 h = 3.6 m (time discretisation: within 2%).
  EXPECT_NEAR(apex, 0.36 * h, 0.02 * 0.36 * h);
  std::size_t awake = 1;
  for (int t = 0; t < 600 * 30 && awake; ++t) awake = stepGroundBodies(world, store, dt);
  EXPECT_EQ(awake, 0u);
  EXPECT_TRUE(store.body[0].sleeping);
  EXPECT_NEAR(store.pos[0].y(), 0.5, 1e-9);
}

}  // namespace
}  // namespace zonesim::zone
