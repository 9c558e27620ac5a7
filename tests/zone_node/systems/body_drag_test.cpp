// The drag keys of `physics:` reach the engine: a body falling under linear drag follows
// v(t) = (m g / k)(1 - exp(-k t / m)) and one under quadratic drag v_t tanh(g t / v_t) with
// v_t = sqrt(m g / c), to RK4's error.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/scene.h"
#include "zone_node/population.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/systems/rigid_bodies.h"

namespace zonesim::zone {
namespace {

constexpr double kG = 9.81;

// Two spheres of 2 kg high in a tall world: nothing touches anything for the 3 s simulated.
std::string dragScene(const char* drag) {
  return std::string(R"(world: {min: [0, 0, 0], max: [100, 2000, 100]}
tick: {dt: 0.02}
seed: 1
zones: {columns: 1, rows: 1}
physics:
  integrator: rk4
  sleep: false
  )") + drag + R"(
  bodies:
    - {name: a, position: [30, 1900, 50], mass: 2}
    - {name: b, position: [70, 1900, 50], mass: 2, velocity: [3, 0, 0]}
)";
}

struct Fall {
  explicit Fall(const std::string& text) : scene(parseScene(text, "drag.yaml")) {
    forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
    bodies = std::make_unique<RigidBodySystem>(scene, 0);
  }
  Vec3 velocityAfter(int ticks, std::size_t named) {
    for (int t = 0; t < ticks; ++t) LoneZone{scene.dt}.step(*bodies, store, std::uint64_t(t));
    return store.vel[*store.indexOf(namedBodyId(scene, named))];
  }
  Scene scene;
  EntityStore store;
  std::unique_ptr<RigidBodySystem> bodies;
};

TEST(BodyDrag, LinearDragKeyIsReadAndFallsToTheClosedForm) {
  Fall fall(dragScene("linear_drag: 0.8"));
  ASSERT_EQ(fall.scene.physics.linear_drag, 0.8);
  const int ticks = 150;
  const double m = 2, k = 0.8, t = ticks * fall.scene.dt;
  const Vec3 v = fall.velocityAfter(ticks, 1);
  EXPECT_NEAR(v.y(), -(m * kG / k) * (1 - std::exp(-k * t / m)), 1e-9);
  EXPECT_NEAR(v.x(), 3 * std::exp(-k * t / m), 1e-9);  // drag acts on every component
  EXPECT_EQ(v.z(), 0.0);
}

TEST(BodyDrag, QuadraticDragKeyIsReadAndFallsToTheClosedForm) {
  Fall fall(dragScene("quadratic_drag: 0.05"));
  ASSERT_EQ(fall.scene.physics.quadratic_drag, 0.05);
  const int ticks = 150;
  const double vt = std::sqrt(2 * kG / 0.05), t = ticks * fall.scene.dt;
  EXPECT_NEAR(fall.velocityAfter(ticks, 0).y(), -vt * std::tanh(kG * t / vt), 1e-8);
}

TEST(BodyDrag, WithoutTheKeysABodyFallsFreely) {
  Fall fall(dragScene("sor_omega: 1.3"));
  EXPECT_EQ(fall.scene.physics.linear_drag, 0.0);
  EXPECT_EQ(fall.scene.physics.quadratic_drag, 0.0);
  const Vec3 v = fall.velocityAfter(100, 1);
  EXPECT_NEAR(v.y(), -kG * 100 * fall.scene.dt, 1e-9);
  EXPECT_EQ(v.x(), 3.0);
}

}  // namespace
}  // namespace zonesim::zone
