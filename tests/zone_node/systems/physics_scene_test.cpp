// scenes/physics_objects.yaml run by the zone's RigidBodySystem: joints keep their bodies
// together, cloths stay pinned and out of bodies, explosions give the closed-form push.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "common/scene.h"
#include "physics/cloth.h"
#include "physics/cloth_collision.h"
#include "physics/shape.h"
#include "zone_node/population.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/systems/rigid_bodies.h"

namespace zonesim::zone {
namespace {

Vec3 vec(const SceneVec3& v) {
  return Vec3(v.x, v.y, v.z);
}

class PhysicsScene : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = loadScene(std::string(ZONESIM_SOURCE_DIR) + "/scenes/physics_objects.yaml");
    forEachInitialEntity(scene_, [&](const EntityRecordData& r) { store_.add(r); });
    bodies_ = std::make_unique<RigidBodySystem>(scene_, 0);
  }
  int named(const std::string& name) const {
    const auto& b = scene_.physics.bodies;
    auto it = std::find_if(b.begin(), b.end(), [&](const SceneBody& s) { return s.name == name; });
    EXPECT_NE(it, b.end()) << name;
    return int(it - b.begin());
  }
  std::size_t at(const std::string& name) const {
    return *store_.indexOf(namedBodyId(scene_, std::size_t(named(name))));
  }
  /// World position of a point given at the scene's start (bodies start unrotated).
  Vec3 carried(const std::string& name, const Vec3& start_point) const {
    std::size_t i = at(name);
    return store_.pos[i] +
           store_.rot[i] * (start_point - vec(scene_.physics.bodies[named(name)].position));
  }
  void step(std::uint64_t tick) { LoneZone{scene_.dt}.step(*bodies_, store_, tick); }

  Scene scene_;
  EntityStore store_;
  std::unique_ptr<RigidBodySystem> bodies_;
};

TEST_F(PhysicsScene, JointsKeepTheirBodiesTogether) {
  ASSERT_EQ(bodies_->joints(), 0u);
  const Vec3 pivot(8, 8, 8), hinge(19.5, 1.5, 8);
  double ball_gap = 0, hinge_gap = 0, tilt = 0, rod_error = 0, lowest_bell = 1e9;
  for (std::uint64_t t = 0; t < 180; ++t) {
    step(t);
    ball_gap = std::max(ball_gap, (carried("bob", pivot) - pivot).norm());
    hinge_gap = std::max(hinge_gap, (carried("door", hinge) - hinge).norm());
    tilt = std::max(tilt, std::acos(std::min(1.0, (store_.rot[at("door")] * Vec3::UnitY()).y())));
    const double rod = (store_.pos[at("bell_b")] - store_.pos[at("bell_a")]).norm();
    rod_error = std::max(rod_error, std::abs(rod - std::sqrt(1.25)));
    lowest_bell = std::min(lowest_bell, store_.pos[at("bell_a")].y());
  }
  EXPECT_EQ(bodies_->joints(), 3u);
  // The door turned at about its 1 rad/s for 3 s: the angle of its x axis about y.
  const Vec3 x = store_.rot[at("door")] * Vec3::UnitX();
  const double turned = std::atan2(-x.z(), x.x());
  std::printf(
      "3 s at 60 Hz: ball joint gap %.2e m, hinge gap %.2e m, hinge tilt %.2e rad, door"
      " turned %.4f rad at 1 rad/s, distance joint error %.2e m\n",
      ball_gap, hinge_gap, tilt, turned, rod_error);
  // A step of length v h along the swing leaves the circle by (v h)^2 / (2 L); the Baumgarte
  // bias removes beta = 0.2 of the gap per step, so it settles at (v h)^2 / (2 L beta), largest
  // at the bottom: v^2 = 2 g L (1 - cos 30 deg). Two substeps of 1/120 s.
  const double h = scene_.dt / scene_.physics.substeps, L = 2.0;
  const double v2 = 2 * 9.81 * L * (1 - std::cos(M_PI / 6));
  const double lag = v2 * h * h / (2 * L * 0.2);
  std::printf("ball joint: Baumgarte lag (v h)^2 / (2 L beta) = %.3e m, measured %.3e m\n", lag,
              ball_gap);
  EXPECT_LT(ball_gap, 1.1 * lag);
  EXPECT_LT(hinge_gap, 1e-3);
  EXPECT_LT(tilt, 1e-3);
  EXPECT_NEAR(turned, 3.0, 0.01);
  EXPECT_LT(rod_error, 1e-2);
  EXPECT_LT(lowest_bell, 0.31);  // The dumbbell fell to the ground.
  // The pendulum swings below the pivot on a 2 m radius.
  EXPECT_NEAR((store_.pos[at("bob")] - pivot).norm(), 2.0, 1e-3);
}

TEST_F(PhysicsScene, ClothsStayPinnedAndOutOfTheTable) {
  ASSERT_EQ(bodies_->clothCount(), 2u);
  const physics::Cloth& hanging = bodies_->cloth(0);
  const Vec3 pin0 = hanging.positions()[hanging.index(0, 0)];
  const Vec3 pin1 = hanging.positions()[hanging.index(11, 0)];
  const physics::Shape table = physics::Shape::box(Vec3(0.6, 0.5, 0.6));
  double deepest = 0;
  for (std::uint64_t t = 0; t < 180; ++t) {
    step(t);
    const physics::Cloth& c = bodies_->cloth(1);
    std::size_t i = at("table");
    for (const Vec3& p : c.positions()) {
      Vec3 n;
      deepest =
          std::max(deepest, c.desc().thickness -
                                physics::signedDistance(table, store_.pos[i], store_.rot[i], p, n));
    }
  }
  const physics::Cloth& over = bodies_->cloth(1);
  const Vec3 middle = over.positions()[over.index(7, 7)];
  const double table_top = store_.pos[at("table")].y() + 0.5;
  double lowest = 1e9;
  for (const Vec3& p : hanging.positions()) lowest = std::min(lowest, p.y());
  std::printf(
      "cloths after 3 s: pins moved %.1e / %.1e m, hanging cloth %.3f m below its pins,"
      " kinetic energy %.2e J; cloth on the table: middle %.6f m over the top (thickness"
      " %.3f), deepest below the thickness %.2e m\n",
      (hanging.positions()[hanging.index(0, 0)] - pin0).norm(),
      (hanging.positions()[hanging.index(11, 0)] - pin1).norm(), 6.0 - lowest,
      hanging.kineticEnergy(), middle.y() - table_top, over.desc().thickness, deepest);
  EXPECT_EQ(hanging.positions()[hanging.index(0, 0)], pin0);
  EXPECT_EQ(hanging.positions()[hanging.index(11, 0)], pin1);
  EXPECT_LT(lowest, 6.0 - 1.1);  // It hangs its full height (and sags) below the pins.
  EXPECT_NEAR(middle.y() - table_top, over.desc().thickness, 2e-3);
  EXPECT_LT(deepest, 2e-3);
}

// A cloth 500 times the default stiffness: with implicit_euler the zone steps it once per
// tick (semi-implicit would need about 700 sub-steps of a 1/60 s tick), and it hangs still.
TEST(PhysicsSceneCloth, AnImplicitClothTakesOneSubStepPerTickAndHangs) {
  const Scene scene = parseScene(R"(world: {min: [0, 0, 0], max: [20, 10, 20]}
tick: {dt: 0.0166666666666666667}
seed: 1
zones: {columns: 1, rows: 1}
physics:
  cloths:
    - {origin: [5, 6, 5], columns: 12, rows: 12, spacing: 0.1, stiffness: 100000,
       shear_stiffness: 25000, bend_stiffness: 5000, damping: 0.5, integrator: implicit_euler,
       pins: [[0, 0], [11, 0]]}
)",
                                 "implicit_cloth.yaml");
  EntityStore store;
  RigidBodySystem bodies(scene, 0);
  ASSERT_EQ(bodies.clothCount(), 1u);
  EXPECT_EQ(bodies.clothSubsteps(0), 1);
  const physics::Cloth& cloth = bodies.cloth(0);
  EXPECT_EQ(cloth.desc().integrator, physics::ClothIntegrator::ImplicitEuler);
  const Vec3 pin = cloth.positions()[cloth.index(0, 0)];
  double fastest = 0;
  for (std::uint64_t t = 0; t < 180; ++t) {
    LoneZone{scene.dt}.step(bodies, store, t);
    for (const Vec3& v : cloth.velocities()) fastest = std::max(fastest, v.norm());
  }
  double lowest = 1e9;
  for (const Vec3& p : cloth.positions()) lowest = std::min(lowest, p.y());
  std::printf(
      "implicit cloth, k 1e5, 1 sub-step per tick: fastest particle %.3f m/s, hangs %.4f "
      "m below its pins, kinetic energy after 3 s %.2e J\n",
      fastest, 6.0 - lowest, cloth.kineticEnergy());
  EXPECT_EQ(cloth.positions()[cloth.index(0, 0)], pin);
  EXPECT_LT(fastest, 10.0);             // a swing, not a blow-up
  EXPECT_GT(6.0 - lowest, 1.1 * 0.99);  // its full height below the pins, barely stretched
  EXPECT_LT(6.0 - lowest, 1.1 * 1.05);
  EXPECT_TRUE(std::isfinite(cloth.kineticEnergy()));
}

TEST_F(PhysicsScene, ExplosionsPushTheSpheresOutwardByTheClosedForm) {
  // Radial speed of each sphere away from its explosion; frictionless on flat ground, only the
  // explosion changes horizontal momentum.
  auto radial = [&](std::initializer_list<const char*> names, const Vec3& centre) {
    double lo = 1e9, hi = -1e9;
    for (const char* n : names) {
      std::size_t i = at(n);
      Vec3 out = store_.pos[i] - centre;
      out.y() = 0;
      const double v = store_.vel[i].dot(out.normalized());
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    return std::pair(lo, hi);
  };
  const Vec3 ring(30, 0.5, 10), blast(10, 0.5, 30);
  const auto ring_names = {"ring_e", "ring_w", "ring_n", "ring_s"};
  const auto blast_names = {"blast_e", "blast_w", "blast_n", "blast_s"};
  // Tick 30 starts at t = 0.5 s (the impulse); ticks 60-89 carry the 0.5 s blast.
  for (std::uint64_t t = 0; t < 30; ++t) step(t);
  EXPECT_LT(std::abs(radial(ring_names, ring).second), 1e-9);
  step(30);
  auto [ring_lo, ring_hi] = radial(ring_names, ring);
  for (std::uint64_t t = 31; t < 60; ++t) step(t);
  EXPECT_LT(std::abs(radial(blast_names, blast).second), 1e-9);
  for (std::uint64_t t = 60; t < 75; ++t) step(t);
  auto [half_lo, half_hi] = radial(blast_names, blast);
  for (std::uint64_t t = 75; t < 120; ++t) step(t);
  auto [blast_lo, blast_hi] = radial(blast_names, blast);
  std::printf(
      "impulse 10 N s, linear falloff at 3 of 6 m on 5 kg: radial %.12f..%.12f m/s"
      " (1); blast 20 N constant for 0.5 s on 5 kg: %.12f..%.12f m/s after 0.25 s (1),"
      " %.12f..%.12f after (2)\n",
      ring_lo, ring_hi, half_lo, half_hi, blast_lo, blast_hi);
  EXPECT_NEAR(ring_lo, 1.0, 1e-9);
  EXPECT_NEAR(ring_hi, 1.0, 1e-9);
  EXPECT_NEAR(half_lo, 1.0, 1e-9);
  EXPECT_NEAR(half_hi, 1.0, 1e-9);
  EXPECT_NEAR(blast_lo, 2.0, 1e-9);
  EXPECT_NEAR(blast_hi, 2.0, 1e-9);
}

}  // namespace
}  // namespace zonesim::zone
