#include "zone_node/zone_node.h"

#include <gtest/gtest.h>

#include "zone_fixture.h"

namespace zonesim::zone {
namespace {

TEST(ZoneNode, ASingleZoneConservesItsEntitiesAndSkipsIdleSystems) {
  Scene s = testing::npcScene(300);
  ZoneNode node(s, MPI_COMM_WORLD, testing::localZone(1));
  ASSERT_EQ(node.size(), 1);
  EXPECT_EQ(node.store().size(), 300u);
  for (int t = 0; t < 120; ++t) {
    node.tick();
    EXPECT_EQ(node.counters().migrated_out, 0u);
    EXPECT_EQ(node.counters().bodies_awake, 0u);     // no rigid bodies: physics never entered
    EXPECT_EQ(node.counters().particles_alive, 0u);  // no emitters: nothing on the GPU
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
