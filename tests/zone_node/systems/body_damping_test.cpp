// The damping keys of physics.bodies (and rigid_body populations) reach the engine: a damped
// body's velocities decay by the engine's exact discrete factor 1 / (1 + c dt) per step, close
// to exp(-c t); undamped spinning bodies in free flight keep their angular velocity (gravity
// exerts no torque about the centre of mass).
#include <gtest/gtest.h>

#include <cmath>

#include "common/scene.h"
#include "zone_node/population.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/systems/rigid_bodies.h"

namespace zonesim::zone {
namespace {

// High in a tall world and 40 m apart: nothing touches anything for the 2 s simulated.
constexpr const char* kScene = R"(world: {min: [0, 0, 0], max: [100, 400, 100]}
tick: {dt: 0.02}
seed: 1
zones: {columns: 1, rows: 1}
physics:
  sleep: false
  bodies:
    - {name: damped, position: [20, 300, 50], velocity: [4, 0, 0], angular_velocity: [0, 2, 0],
       linear_damping: 0.5, angular_damping: 0.25}
    - {name: box, shape: box, size: [1, 2, 3], position: [60, 300, 50], angular_velocity: [0, 3, 0]}
    - {name: ball, position: [60, 300, 90], angular_velocity: [1, -2, 0.5]}
populations:
  - {kind: rigid_body, count: 1, linear_damping: 0.75, angular_damping: 0.5, region: {min: [0, 0, 0], max: [10, 0, 10]}}
)";
constexpr int kTicks = 100;

class BodyDamping : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = parseScene(kScene, "damping.yaml");
    forEachInitialEntity(scene_, [&](const EntityRecordData& r) { store_.add(r); });
    bodies_ = std::make_unique<RigidBodySystem>(scene_, 0);
  }
  std::size_t named(std::size_t k) const { return *store_.indexOf(namedBodyId(scene_, k)); }
  void step(std::uint64_t tick) { LoneZone{scene_.dt}.step(*bodies_, store_, tick); }
  void run() {
    for (std::uint64_t t = 0; t < kTicks; ++t) step(t);
  }
  /// v0 after n steps of the engine's damping v /= 1 + c dt.
  double discrete(double v0, double c) const {
    for (int n = 0; n < kTicks; ++n) v0 /= 1.0 + scene_.dt * c;
    return v0;
  }

  Scene scene_;
  EntityStore store_;
  std::unique_ptr<RigidBodySystem> bodies_;
};

TEST_F(BodyDamping, ADampedBodysVelocitiesDecayByTheDiscreteFactor) {
  ASSERT_EQ(scene_.physics.bodies[0].linear_damping, 0.5);
  run();
  const std::size_t i = named(0);
  const double t = kTicks * scene_.dt;
  // Horizontal: no force but the damping (gravity acts along y only).
  EXPECT_NEAR(store_.vel[i].x(), discrete(4, 0.5), 1e-12);
  EXPECT_NEAR(store_.vel[i].x(), 4 * std::exp(-0.5 * t), 0.01 * 4);  // first order in c dt
  EXPECT_NEAR(store_.vel[i].z(), 0, 1e-15);
  EXPECT_NEAR(store_.body[i].angular_velocity.y(), discrete(2, 0.25), 1e-12);
  EXPECT_NEAR(store_.body[i].angular_velocity.y(), 2 * std::exp(-0.25 * t), 0.01 * 2);
}

TEST_F(BodyDamping, APopulationsDampingReachesItsBodies) {
  std::size_t i = store_.size();
  for (std::size_t k = 0; k < store_.size(); ++k)
    if (store_.body[k].linear_damping == 0.75) i = k;
  ASSERT_LT(i, store_.size());
  EXPECT_EQ(store_.body[i].angular_damping, 0.5);
  const double vx0 = store_.vel[i].x(), wx0 = store_.body[i].angular_velocity.x();
  ASSERT_NE(vx0, 0.0);  // populations start with a random horizontal velocity and spin
  for (std::uint64_t t = 0; t < 10; ++t) step(t);
  double vx = vx0, wx = wx0;
  for (int n = 0; n < 10; ++n) {
    vx /= 1.0 + scene_.dt * 0.75;
    wx /= 1.0 + scene_.dt * 0.5;
  }
  EXPECT_NEAR(store_.vel[i].x(), vx, 1e-12);  // still in the air: dropped from 10 m
  EXPECT_NEAR(store_.body[i].angular_velocity.x(), wx, 1e-12);
}

TEST_F(BodyDamping, UndampedSpinningBodiesKeepTheirAngularVelocity) {
  const std::size_t box = named(1), ball = named(2);
  for (std::uint64_t t = 0; t < kTicks; ++t) {
    step(t);
    // About a principal axis: angular velocity and angular momentum (I_y w) stay put.
    EXPECT_NEAR((store_.body[box].angular_velocity - Vec3(0, 3, 0)).norm(), 0, 1e-12);
    EXPECT_NEAR((store_.rot[box] * Vec3::UnitY() - Vec3::UnitY()).norm(), 0, 1e-9);
    // A sphere's inertia is isotropic: any axis.
    EXPECT_NEAR((store_.body[ball].angular_velocity - Vec3(1, -2, 0.5)).norm(), 0, 1e-12);
  }
  EXPECT_GT(std::abs(store_.vel[box].y()), 1.0);  // they did fly, and fall
}

}  // namespace
}  // namespace zonesim::zone
