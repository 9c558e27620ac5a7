// scenes/set_pieces.yaml in one RigidBodySystem: static and kinematic scene bodies (not
// entities) act on the dynamic ones as the closed forms say, and scene rotations are applied.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "common/scene.h"
#include "zone_node/zone_fixture.h"
#include "zone_node/population.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/systems/rigid_bodies.h"

namespace zonesim::zone {
namespace {

class SetPieces : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = loadScene(std::string(ZONESIM_SOURCE_DIR) + "/scenes/set_pieces.yaml");
    forEachInitialEntity(scene_, [&](const EntityRecordData& r) { store_.add(r); });
    bodies_ = std::make_unique<RigidBodySystem>(scene_, 0);
  }
  std::size_t named(const std::string& name) const {
    const auto& b = scene_.physics.bodies;
    auto it = std::find_if(b.begin(), b.end(), [&](const SceneBody& s) { return s.name == name; });
    EXPECT_NE(it, b.end()) << name;
    return std::size_t(it - b.begin());
  }
  std::size_t at(const std::string& name) const {
    return *store_.indexOf(namedBodyId(scene_, named(name)));
  }
  void run(std::uint64_t from, std::uint64_t to) {
    LoneZone lone{scene_.dt};
    for (std::uint64_t t = from; t < to; ++t) lone.step(*bodies_, store_, t);
  }
  double seconds(std::uint64_t ticks) const { return double(ticks) * scene_.dt; }

  Scene scene_;
  EntityStore store_;
  std::unique_ptr<RigidBodySystem> bodies_;
};

TEST_F(SetPieces, OnlyDynamicBodiesAreEntitiesAndStartAsRotated) {
  std::size_t bodies = 0;
  for (std::size_t i = 0; i < store_.size(); ++i) bodies += store_.kind[i] == EntityKind::RigidBody;
  EXPECT_EQ(bodies, 5u);  // slider, holder, rider, spinner, turned
  for (const char* fixed : {"ramp", "platform", "turntable"})
    EXPECT_FALSE(store_.indexOf(namedBodyId(scene_, named(fixed)))) << fixed;
  // 45 degrees about y: the box's x axis points along (cos 45, 0, -sin 45).
  const Vec3 x = store_.rot[at("turned")] * Vec3::UnitX();
  EXPECT_NEAR(x.x(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(x.z(), -std::sqrt(0.5), 1e-15);
}

TEST_F(SetPieces, BoxesOnTheStaticRampSlideOrHoldByTheirFriction) {
  // Friction of a pair is sqrt(mu_a mu_b); down a 20 degree slope a box accelerates at
  // g (sin 20 - mu cos 20) when mu < tan 20 and holds otherwise.
  const double theta = M_PI / 9, g = 9.81;
  const double mu_slide = std::sqrt(0.3 * 0.1), mu_hold = std::sqrt(0.3 * 1.0);
  ASSERT_LT(mu_slide, std::tan(theta));
  ASSERT_GT(mu_hold, std::tan(theta));
  const double expected = g * (std::sin(theta) - mu_slide * std::cos(theta));
  const Vec3 down_slope(-std::cos(theta), -std::sin(theta), 0);
  run(0, 30);  // settle onto the ramp (they start 5 mm above it)
  const Vec3 hold_start = store_.pos[at("holder")];
  const double v0 = store_.vel[at("slider")].dot(down_slope);
  run(30, 90);
  const double v1 = store_.vel[at("slider")].dot(down_slope);
  const double measured = (v1 - v0) / seconds(60);
  const double held = (store_.pos[at("holder")] - hold_start).norm();
  std::printf(
      "slide down 20 deg at mu %.4f: %.5f m/s^2 (closed form %.5f, error %.2e); box at"
      " mu %.4f moved %.2e m in 1 s\n",
      mu_slide, measured, expected, std::abs(measured / expected - 1), mu_hold, held);
  EXPECT_NEAR(measured, expected, 0.01 * expected);
  EXPECT_LT(held, 1e-4);
}

TEST_F(SetPieces, APlatformCarriesItsBoxAndATurntableTurnsItsBox) {
  const double v = 1.0, w = 0.5;
  const Vec3 axis(30, 0, 20);
  run(0, 60);
  const Vec3 offset0 = store_.pos[at("rider")] - Vec3(16 + v * seconds(60), 1, 30);
  const double r0 = (store_.pos[at("spinner")] - axis).cwiseProduct(Vec3(1, 0, 1)).norm();
  run(60, 240);
  const Vec3 offset1 = store_.pos[at("rider")] - Vec3(16 + v * seconds(240), 1, 30);
  const Vec3 rider_v = store_.vel[at("rider")];
  const Vec3 spin_r = (store_.pos[at("spinner")] - axis).cwiseProduct(Vec3(1, 0, 1));
  const Vec3 spin_v = store_.vel[at("spinner")];
  const double spin_w = store_.body[at("spinner")].angular_velocity.y();
  // On a turntable at w a co-rotating box moves at w x r and turns at w.
  const double tangential = spin_v.norm() / spin_r.norm();
  std::printf(
      "rider: velocity x %.6f m/s (1), drift on the platform %.2e m over 3 s; spinner:"
      " radius %.4f -> %.4f m, orbit %.6f rad/s and spin %.6f rad/s (0.5)\n",
      rider_v.x(), (offset1 - offset0).norm(), r0, spin_r.norm(), tangential, spin_w);
  EXPECT_NEAR(rider_v.x(), v, 1e-3);
  EXPECT_LT((offset1 - offset0).norm(), 1e-3);
  // Each step carries the box along the tangent (the contact sees the table's velocity w x r,
  // not its circle), so it spirals out by r (w dt)^2 / 2 a step, a first-order error.
  const double spiral = r0 * std::pow(w * scene_.dt, 2) / 2 * 180;
  std::printf("spiral outward %.3e m over 180 steps (predicted r (w dt)^2 / 2 per step: %.3e)\n",
              spin_r.norm() - r0, spiral);
  EXPECT_NEAR(spin_r.norm() - r0, spiral, 0.2 * spiral);
  EXPECT_NEAR(tangential, w, 5e-3);
  EXPECT_NEAR(spin_w, w, 5e-3);
  // Still turned by 45 degrees and at rest on the ground.
  const Vec3 x = store_.rot[at("turned")] * Vec3::UnitX();
  EXPECT_NEAR(std::atan2(-x.z(), x.x()), M_PI / 4, 1e-3);
}

TEST_F(SetPieces, SceneMistakesNameTheirLine) {
  auto fails = [](const std::string& body, const std::string& expect) {
    testing::expectSceneError(testing::withSmallWorld("physics:\n  bodies:\n    - " + body + "\n"),
                              expect);
  };
  fails("{name: a, motion: static, position: [1, 1, 1], velocity: [1, 0, 0]}",
        "t.yaml:7: physics.bodies[0].velocity: a static body does not move");
  fails("{name: a, motion: kinematic, position: [1, 1, 1], mass: 3}",
        "t.yaml:7: physics.bodies[0].mass: only dynamic bodies have a mass");
  fails("{name: a, position: [1, 1, 1], rotation: {axis: [0, 0, 0], degrees: 10}}",
        "must not be the zero vector");
  fails("{name: a, motion: hovering, position: [1, 1, 1]}", "physics.bodies[0].motion");
}

}  // namespace
}  // namespace zonesim::zone
