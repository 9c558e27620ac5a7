#include "zone_node/zone_node.h"

#include <gtest/gtest.h>

#include "zone_node/zone_fixture.h"

namespace zonesim::zone {
namespace {

// A scene with work for the AI and physics phases and none for the others: every tick the
// walkers move and the bodies are stepped, while migration, particles and agents count nothing.
TEST(ZoneNode, ASingleZoneConservesItsEntitiesAndWorksOnlyWhereThereIsWork) {
  Scene s = testing::npcScene(300);
  RigidBodyPopulation bodies;
  bodies.count = 5;
  bodies.region = s.world;
  s.rigid_bodies.push_back(bodies);
  ZoneNode node(s, MPI_COMM_WORLD, testing::localZone(1));
  ASSERT_EQ(node.size(), 1);
  ASSERT_EQ(node.store().size(), 305u);
  for (int t = 0; t < 120; ++t) {
    std::vector<Vec3> before = node.store().pos;
    node.tick();
    const EntityStore& st = node.store();
    ASSERT_EQ(st.size(), 305u);
    int walked = 0;
    for (std::size_t i = 0; i < st.size(); ++i)
      walked += st.kind[i] == EntityKind::Npc && st.pos[i] != before[i];
    EXPECT_GT(walked, 250) << "tick " << t;          // ai: nearly every walker moved
    EXPECT_EQ(node.counters().bodies_awake, 5u);     // physics: the bodies never sleep here
    EXPECT_EQ(node.counters().migrated_out, 0u);     // one zone: nobody leaves
    EXPECT_EQ(node.counters().migration_bytes, 0u);  // nor is anything sent
    EXPECT_EQ(node.counters().particles_alive, 0u);  // no emitters
    EXPECT_EQ(node.counters().agents, 0u);           // no agents
    EXPECT_EQ(node.counters().quarantined, 0u);
  }
  EXPECT_EQ(node.conservation().checks, 120u);
  EXPECT_EQ(node.conservation().failures, 0u);
  EXPECT_EQ(node.particleBackend(), "none");
}

TEST(ZoneNode, RigidBodiesAndEmittersRunWhenTheSceneHasThem) {
  Scene s = testing::npcScene(10);
  RigidBodyPopulation bodies;
  bodies.count = 5;
  bodies.region = s.world;
  s.rigid_bodies.push_back(bodies);
  EmitterPopulation emitters;
  emitters.count = 2;
  emitters.rate = 300;
  emitters.region = s.world;
  s.emitters.push_back(emitters);
  ZoneNode node(s, MPI_COMM_WORLD, testing::localZone(1));
  node.tick();
  EXPECT_EQ(node.counters().bodies_awake, 5u);
  for (int t = 0; t < 30; ++t) node.tick();
  // 2 emitters x 300/s x ~1 s, none expired yet (lifetime 2 s).
  EXPECT_NEAR(double(node.counters().particles_alive), 2 * 300 * 31.0 / 30, 4.0);
}

}  // namespace
}  // namespace zonesim::zone
