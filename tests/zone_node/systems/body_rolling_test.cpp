// A scene's rolling_resistance reaches the engine through the zone: a sphere rolling on the
// ground decelerates at the analytic (5/7) c_rr g (a solid sphere rolling without slipping
// under a resisting torque c_rr R N), and one without it keeps rolling.
#include <gtest/gtest.h>

#include "common/scene.h"
#include "zone_node/population.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/systems/rigid_bodies.h"

namespace zonesim::zone {
namespace {

// Radius 0.5 resting on the ground at y = 0, rolling along +x without slipping (w = v / R).
constexpr const char* kScene = R"(world: {min: [0, 0, 0], max: [200, 20, 100]}
tick: {dt: 0.02}
seed: 1
zones: {columns: 1, rows: 1}
physics:
  sleep: false
  bodies:
    - {name: slowing, position: [10, 0.5, 30], velocity: [3, 0, 0], angular_velocity: [0, 0, -6],
       friction: 0.8, rolling_resistance: 0.05}
    - {name: free, position: [10, 0.5, 70], velocity: [3, 0, 0], angular_velocity: [0, 0, -6],
       friction: 0.8}
)";

TEST(BodyRolling, ASceneBodysRollingResistanceSlowsItAtTheAnalyticRate) {
  const Scene scene = parseScene(kScene, "rolling.yaml");
  ASSERT_EQ(scene.physics.bodies[0].rolling_resistance, 0.05);
  // The scene names no solver: the default, the wide soft step, which does not solve rolling
  // resistance, gives way to the soft step.
  ASSERT_EQ(scene.physics.solver, PhysicsSettings::Solver::SoftStep);
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  RigidBodySystem bodies(scene, 0);
  const std::size_t slowing = *store.indexOf(namedBodyId(scene, 0));
  const std::size_t free = *store.indexOf(namedBodyId(scene, 1));
  EXPECT_EQ(store.body[slowing].rolling_resistance, 0.05);
  constexpr int kTicks = 150;  // 3 s: v = 3 - (5/7) 0.05 g t = 1.949 m/s, still rolling
  for (std::uint64_t t = 0; t < kTicks; ++t) LoneZone{scene.dt}.step(bodies, store, t);
  const double expected = 3.0 - 5.0 / 7.0 * 0.05 * 9.81 * kTicks * scene.dt;
  EXPECT_NEAR(store.vel[slowing].x(), expected, 0.01 * expected);
  EXPECT_NEAR(store.vel[free].x(), 3.0, 0.01);
}

}  // namespace
}  // namespace zonesim::zone
