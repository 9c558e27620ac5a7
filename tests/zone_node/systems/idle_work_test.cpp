// Idle systems do no work, counted rather than timed (timings are noisy; the idle cost per tick
// is measured by bench/cluster/idle_costs.py): once every body sleeps the engine's world is not
// stepped at all, and a zone of walkers only runs no physics, particles, agents, paths, ghosts
// or publishing.
#include <gtest/gtest.h>

#include "common/scene.h"
#include "zone_node/population.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/systems/rigid_bodies.h"
#include "zone_node/zone_fixture.h"
#include "zone_node/zone_node.h"

namespace zonesim::zone {
namespace {

TEST(IdleWork, SleepingBodiesAreNotStepped) {
  const Scene scene = parseScene(R"(world: {min: [0, 0, 0], max: [60, 20, 60]}
tick: {dt: 0.05}
seed: 5
zones: {columns: 1, rows: 1}
physics: {sleep: true}
populations:
  - {kind: rigid_body, count: 30, shape: box, size: [1, 1, 1], drop_height: [0.6, 0.6],
     region: {min: [5, 0, 5], max: [55, 0, 55]}}
)",
                                 "asleep.yaml");
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  RigidBodySystem bodies(scene, 0);
  LoneZone lone{scene.dt};
  std::uint64_t steps_while_awake = 0, t = 0;
  for (; t < 2000 && (t == 0 || lone.counters.bodies_awake > 0); ++t)
    steps_while_awake += lone.step(bodies, store, t).physics_steps;
  ASSERT_EQ(lone.counters.bodies_awake, 0u) << "the boxes did not settle in 2000 ticks";
  EXPECT_GT(steps_while_awake, 0u);
  // The first tick asleep reads the bodies once; from then on, with the same bodies and nothing
  // to wake them, the system reads none.
  std::uint64_t rows_read_after_the_first = 0;
  for (std::uint64_t k = 0; k < 200; ++k, ++t) {
    const TickCounters& c = lone.step(bodies, store, t);
    ASSERT_EQ(c.physics_steps, 0u) << "tick " << t;
    ASSERT_EQ(c.bodies_awake, 0u);
    if (k > 0) rows_read_after_the_first += c.bodies_checked;
  }
  EXPECT_EQ(rows_read_after_the_first, 0u);
  // A newcomer is seen at once: a box dropped above the others is read, stepped and falls.
  EntityRecordData box = store.record(0);
  box.id = EntityId{1'000'000};
  box.pos.y() += 5;
  box.body.sleeping = false;
  store.add(box);
  const TickCounters& c = lone.step(bodies, store, t);
  EXPECT_EQ(c.bodies_checked, 31u);
  EXPECT_EQ(c.physics_steps, 1u);
  EXPECT_GT(c.bodies_awake, 0u);
}

TEST(IdleWork, AZoneOfWalkersOnlyDoesNoOtherWork) {
  Scene scene = loadScene(std::string(ZONESIM_SOURCE_DIR) + "/scenes/test_npc_only.yaml");
  scene.zones.columns = scene.zones.rows = 1;
  ZoneNode zone(scene, MPI_COMM_WORLD, testing::localZone(0));
  TickCounters sum;
  for (int tick = 0; tick < 200; ++tick) {
    zone.tick();
    const TickCounters& c = zone.counters();
    sum.physics_steps += c.physics_steps;
    sum.bodies_awake += c.bodies_awake;
    sum.particles_alive += c.particles_alive;
    sum.agents += c.agents;
    sum.agent_decisions += c.agent_decisions;
    sum.paths_planned += c.paths_planned;
    sum.ghosts += c.ghosts;
    sum.ghosts_sent += c.ghosts_sent;
    sum.published_states += c.published_states;
    sum.migrated_out += c.migrated_out;
  }
  EXPECT_EQ(zone.store().count(EntityKind::Npc), 500u);
  EXPECT_EQ(sum.physics_steps + sum.bodies_awake + sum.particles_alive, 0u);
  EXPECT_EQ(sum.agents + sum.agent_decisions + sum.paths_planned, 0u);
  EXPECT_EQ(sum.ghosts + sum.ghosts_sent + sum.migrated_out, 0u);
  EXPECT_EQ(sum.published_states, 0u);  // no DDS: no publisher at all
}

}  // namespace
}  // namespace zonesim::zone
