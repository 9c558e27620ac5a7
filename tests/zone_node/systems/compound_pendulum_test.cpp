// A compound body through the zone: a rod with a ball at its end, built as a scene compound
// and hinged to the world at the rod's top, swings with the period of the physical pendulum,
// 2 pi sqrt(I_pivot / (m g d)), with I_pivot and d computed here from the two shapes' own
// formulas (not the engine's compound code); the scene places the parts' frame at the pivot,
// so this also checks that the entity starts at their centre of mass and the hinge's anchor
// lands where the scene put it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "common/scene.h"
#include "zone_node/population.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/systems/rigid_bodies.h"

namespace zonesim::zone {
namespace {

constexpr const char* kScene = R"(world: {min: [0, 0, 0], max: [20, 20, 20]}
tick: {dt: 0.004}
seed: 1
zones: {columns: 1, rows: 1}
physics:
  sleep: false
  velocity_iterations: 20
  bodies:
    - name: pendulum
      shape: compound
      position: [10, 15, 10]
      rotation: {axis: [0, 0, 1], degrees: 5}
      mass: 5
      parts:
        - {shape: box, size: [0.1, 1, 0.1], position: [0, -0.5, 0]}
        - {shape: sphere, radius: 0.2, position: [0, -1.2, 0]}
  joints:
    - {type: hinge, a: pendulum, anchor: [10, 15, 10], axis: [0, 0, 1]}
)";

TEST(CompoundPendulum, SwingsWithThePhysicalPendulumsPeriod) {
  const Scene scene = parseScene(kScene, "pendulum.yaml");
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  const std::size_t i = *store.indexOf(namedBodyId(scene, 0));
  // Volumes (uniform density): the rod 0.1 x 1 x 0.1 centred 0.5 m below the pivot, the ball
  // of radius 0.2 centred 1.2 m below it.
  const double rod = 0.01, ball = 4.0 / 3.0 * std::numbers::pi * 0.008, total = rod + ball;
  const double d = (rod * 0.5 + ball * 1.2) / total;
  const double rho = 5.0 / total;
  const double inertia = rho * (rod * ((0.01 + 1.0) / 12.0 + 0.25) + ball * (0.4 * 0.04 + 1.44));
  const double a0 = 5.0 * std::numbers::pi / 180.0;
  // The entity starts at the centre of mass: d below the pivot, turned 5 degrees about z.
  EXPECT_NEAR(store.pos[i].x(), 10.0 + d * std::sin(a0), 1e-12);
  EXPECT_NEAR(store.pos[i].y(), 15.0 - d * std::cos(a0), 1e-12);

  RigidBodySystem bodies(scene, 0);
  std::vector<double> crossings;
  double x_prev = store.pos[i].x() - 10.0;
  for (std::uint64_t t = 0; t < 2000; ++t) {  // 8 s, about 4 periods
    LoneZone{scene.dt}.step(bodies, store, t);
    const double x = store.pos[i].x() - 10.0;
    if (x_prev > 0.0 && x <= 0.0)
      crossings.push_back((double(t) + x_prev / (x_prev - x)) * scene.dt);
    x_prev = x;
  }
  ASSERT_GE(crossings.size(), 3u);
  const double period = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  // Amplitude a0: T = T0 (1 + a0^2 / 16 + ...).
  const double theory =
      2.0 * std::numbers::pi * std::sqrt(inertia / (5.0 * 9.81 * d)) * (1.0 + a0 * a0 / 16.0);
  std::printf("compound pendulum: period %.5f s, theory %.5f s\n", period, theory);
  EXPECT_NEAR(period / theory, 1.0, 2e-3);
  EXPECT_EQ(bodies.joints(), 1u);
}

}  // namespace
}  // namespace zonesim::zone
