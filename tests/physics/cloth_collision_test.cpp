// Cloth against rigid bodies: a patch falls on the ground and stops at the plane, drapes over
// a fixed sphere, box and capsule without entering them, and a cloth that hits a free body
// conserves the momentum of cloth and body together (two-way coupling).

#include "physics/cloth_collision.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "physics/cloth.h"
#include "physics/world.h"

namespace zonesim::physics {
namespace {

constexpr double kDt = 1.0 / 60.0;
constexpr int kClothSubsteps = 20;

/// A horizontal patch of n x n particles, 0.1 m apart, centred on (0, height, 0).
ClothDesc horizontalPatch(int n, double height) {
  ClothDesc d;
  d.columns = n;
  d.rows = n;
  d.origin = Vec3(-0.05 * (n - 1), height, -0.05 * (n - 1));
  d.column_axis = Vec3::UnitX();
  d.row_axis = Vec3::UnitZ();
  d.spring_damping = 0.5;  // Settles in a few seconds; rest does not depend on it.
  return d;
}

BodyIndex addStatic(World& world, const Shape& shape, const Vec3& at,
                    const Quat& q = Quat::Identity()) {
  BodyDesc b;
  b.type = BodyType::Static;
  b.shape = shape;
  b.position = at;
  b.orientation = q;
  return world.addBody(b);
}

/// Steps world and cloth together for `seconds`; returns the deepest any particle went below
/// `thickness` from any body's surface at the end of a step.
double run(World& world, Cloth& cloth, double seconds) {
  ClothColliders colliders;
  double deepest = 0.0;
  for (int s = 0; s < int(std::lround(seconds / kDt)); ++s) {
    world.step(kDt);
    colliders.gather(world.bodies());
    cloth.step(kDt, kClothSubsteps, &colliders);
    colliders.applyReactions(world);
    const BodyStorage& b = world.bodies();
    for (const Vec3& p : cloth.positions()) {
      for (std::size_t i = 0; i < b.size(); ++i) {
        Vec3 n;
        const double d = signedDistance(b.shape[i], b.position[i], b.orientation[i], p, n);
        deepest = std::max(deepest, cloth.desc().thickness - d);
      }
    }
  }
  return deepest;
}

TEST(ClothCollision, SignedDistanceOfEachShape) {
  Vec3 n;
  const Quat q(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
  const Vec3 c(1, 2, 3);
  // Sphere and capsule: distance to the centre (segment) less the radius.
  EXPECT_NEAR(signedDistance(Shape::sphere(0.5), c, q, c + Vec3(0, 0, 2), n), 1.5, 1e-15);
  EXPECT_NEAR((n - Vec3::UnitZ()).norm(), 0.0, 1e-15);
  const Vec3 up = q * Vec3::UnitY(), side = q * Vec3::UnitX();
  EXPECT_NEAR(signedDistance(Shape::capsule(0.2, 1.0), c, q, c + 0.7 * up + 0.5 * side, n), 0.3,
              1e-14);
  EXPECT_NEAR(signedDistance(Shape::capsule(0.2, 1.0), c, q, c + 1.5 * up, n), 0.3, 1e-14);
  // Box: outside a face, outside a corner, and inside (negative, out through the nearest face).
  const Shape box = Shape::box(Vec3(1, 2, 3));
  EXPECT_NEAR(signedDistance(box, c, q, c + q * Vec3(0, 2.5, 0), n), 0.5, 1e-14);
  EXPECT_NEAR((n - up).norm(), 0.0, 1e-14);
  EXPECT_NEAR(signedDistance(box, c, q, c + q * Vec3(2, 3, 3), n), std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(signedDistance(box, c, q, c + q * Vec3(0.8, 0, 0), n), -0.2, 1e-14);
  EXPECT_NEAR((n - side).norm(), 0.0, 1e-14);
  // Plane through c with normal up.
  EXPECT_NEAR(signedDistance(Shape::plane(), c, q, c + 0.25 * up - 4.0 * side, n), 0.25, 1e-14);
}

TEST(ClothCollision, FallingPatchStopsAtTheGround) {
  World world;
  addStatic(world, Shape::plane(), Vec3::Zero());
  ClothDesc d = horizontalPatch(10, 1.0);
  Cloth cloth(d);
  const double deepest = run(world, cloth, 3.0);
  double lo = 1e9, hi = -1e9;
  for (const Vec3& p : cloth.positions()) {
    lo = std::min(lo, p.y());
    hi = std::max(hi, p.y());
  }
  std::printf(
      "cloth on the ground: heights %.9f..%.9f m (thickness %.3f), kinetic energy %.2e J,"
      " deepest %.2e m\n",
      lo, hi, d.thickness, cloth.kineticEnergy(), deepest);
  // It lies flat on the plane at its thickness, at rest, and never went in.
  EXPECT_NEAR(lo, d.thickness, 1e-9);
  EXPECT_NEAR(hi, d.thickness, 1e-6);
  EXPECT_LT(cloth.kineticEnergy(), 1e-8);
  EXPECT_LT(deepest, 1e-9);
}

TEST(ClothCollision, PatchDrapesOverAFixedSphereWithoutEnteringIt) {
  World world;
  const double r = 0.5;
  addStatic(world, Shape::plane(), Vec3(0, -r, 0));
  addStatic(world, Shape::sphere(r), Vec3::Zero());
  ClothDesc d = horizontalPatch(21, r + 0.2);
  d.friction = 0.5;
  Cloth cloth(d);
  const double deepest = run(world, cloth, 5.0);
  const Vec3 top = cloth.positions()[cloth.index(10, 10)];
  double lowest_corner = 1e9;
  for (int c : {0, 20})
    for (int k : {0, 20})
      lowest_corner = std::min(lowest_corner, cloth.positions()[cloth.index(c, k)].y());
  std::printf(
      "draped over a sphere: top particle at y %.6f (r + thickness %.6f), corners down to"
      " %.4f m, kinetic energy %.2e J, deepest below thickness %.2e m\n",
      top.y(), r + d.thickness, lowest_corner, cloth.kineticEnergy(), deepest);
  EXPECT_NEAR(top.y(), r + d.thickness, 1e-4);
  EXPECT_NEAR(top.x(), 0.0, 1e-6);         // Symmetric drape: nothing slid sideways.
  EXPECT_LT(deepest, 1e-9);                // No particle ever inside the sphere (or the ground).
  EXPECT_LT(lowest_corner, 0.0);           // The corners hang below the sphere's equator.
  EXPECT_LT(cloth.kineticEnergy(), 1e-4);  // 4.4 kg: rms speed under 7 mm/s, still settling
}

TEST(ClothCollision, PatchRestsOnABoxAndACapsuleWithoutEnteringThem) {
  struct Case {
    const char* name;
    Shape shape;
    Quat q;
    double top;  // height of the shape's highest point above its centre
  };
  const Quat lying(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
  for (const Case& k : {Case{"box", Shape::box(Vec3(0.3, 0.2, 0.3)), Quat::Identity(), 0.2},
                        Case{"capsule", Shape::capsule(0.2, 0.4), lying, 0.2}}) {
    World world;
    addStatic(world, Shape::plane(), Vec3(0, -0.5, 0));
    addStatic(world, k.shape, Vec3::Zero(), k.q);
    ClothDesc d = horizontalPatch(15, 0.4);
    d.friction = 0.5;
    Cloth cloth(d);
    const double deepest = run(world, cloth, 4.0);
    const Vec3 top = cloth.positions()[cloth.index(7, 7)];
    std::printf("%s: top particle at y %.6f (top + thickness %.6f), deepest %.2e m\n", k.name,
                top.y(), k.top + d.thickness, deepest);
    EXPECT_NEAR(top.y(), k.top + d.thickness, 1e-4) << k.name;
    EXPECT_LT(deepest, 1e-9) << k.name;
  }
}

TEST(ClothCollision, ClothHittingAFreeBodyConservesTotalMomentum) {
  // No gravity: a cloth flying down at 2 m/s hits a free sphere. The springs are internal and
  // each particle's velocity change goes to the body as the opposite impulse.
  World world;
  world.forces().gravity = Vec3::Zero();
  BodyDesc b;
  b.shape = Shape::sphere(0.3);
  b.density = 200.0;
  b.position = Vec3(0.05, 0.0, -0.03);  // off centre, so the body also starts to spin
  const BodyIndex ball = world.addBody(b);
  ClothDesc d = horizontalPatch(12, 0.5);
  d.gravity = Vec3::Zero();
  Cloth cloth(d);
  for (Vec3& v : cloth.velocities()) v = Vec3(0, -2, 0);
  const double mass = 1.0 / world.bodies().inv_mass[ball];
  const Vec3 before = cloth.momentum();
  run(world, cloth, 1.0);
  const Vec3 after = cloth.momentum() + mass * world.bodies().linear_velocity[ball];
  std::printf(
      "cloth %.4f kg onto a %.3f kg sphere: momentum before %.15f, after %.15f (y), ball"
      " velocity %.4f m/s\n",
      cloth.positions().size() * d.particle_mass, mass, before.y(), after.y(),
      world.bodies().linear_velocity[ball].y());
  EXPECT_NEAR((after - before).norm(), 0.0, 1e-12 * before.norm());
  EXPECT_LT(world.bodies().linear_velocity[ball].y(), -0.01);  // The ball was pushed down.
}

}  // namespace
}  // namespace zonesim::physics
