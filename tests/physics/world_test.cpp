#include "physics/world.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "physics/box_column.h"
#include "rebound.h"
#include "slope.h"

namespace zonesim::physics {
namespace {

Quat about(const Vec3& axis, double degrees) {
  return Quat(Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, axis.normalized()));
}

/// A static plane through the origin, facing +y.
void addGround(World& world) {
  BodyDesc ground;
  ground.type = BodyType::Static;
  ground.shape = Shape::plane();
  world.addBody(ground);
}

double mass(const World& w, BodyIndex i) {
  return 1.0 / w.bodies().inv_mass[i];
}

TEST(World, ElasticCollisionConservesMomentumAndEnergy) {
  World world;
  world.forces().gravity.setZero();
  BodyDesc a;
  a.shape = Shape::sphere(0.5);
  a.position = Vec3(-2, 0, 0);
  a.linear_velocity = Vec3(2, 0, 0);
  a.restitution = 1.0;
  a.friction = 0.0;
  BodyDesc b = a;
  b.shape = Shape::sphere(0.3);
  b.density = 3000.0;
  b.position = Vec3(1, 0.4, 0.1);  // Off-centre: the impulse is oblique.
  b.linear_velocity = Vec3(-1, 0, 0);
  const BodyIndex ia = world.addBody(a), ib = world.addBody(b);
  const auto momentum = [&] {
    return Vec3(mass(world, ia) * world.bodies().linear_velocity[ia] +
                mass(world, ib) * world.bodies().linear_velocity[ib]);
  };
  const auto energy = [&] {
    return 0.5 * mass(world, ia) * world.bodies().linear_velocity[ia].squaredNorm() +
           0.5 * mass(world, ib) * world.bodies().linear_velocity[ib].squaredNorm();
  };
  const Vec3 p0 = momentum();
  const double e0 = energy();
  for (int i = 0; i < 120; ++i) world.step(1.0 / 60.0);
  // They did collide: B, the lighter one, now moves forwards in x.
  ASSERT_GT(world.bodies().linear_velocity[ib].x(), 0.0);
  EXPECT_LT((momentum() - p0).norm() / p0.norm(), 1e-14);
  EXPECT_NEAR(energy() / e0, 1.0, 1e-14);
  EXPECT_LT(world.bodies().angular_velocity[ia].norm(), 1e-12);
}

TEST(World, RestitutionGivesTheExpectedReboundHeight) {
  // Dropped from h onto a plane, a ball with restitution e rises to e^2 h.
  const double h = 2.0, e = 0.6, r = 0.5, dt = 1.0 / 1000.0;
  const double apex = testing::reboundApex(WorldSettings{}, h, e, r, dt);
  std::printf("rebound apex %.5f m, expected %.5f m\n", apex, e * e * h);
  EXPECT_NEAR(apex / (e * e * h), 1.0, 0.01);
}

TEST(World, BoxOnSlopeHoldsAboveTanAngleAndSlidesBelow) {
  const double tan30 = std::tan(std::numbers::pi / 6.0), g = 9.81;
  const double stuck = testing::slideOnSlope(WorldSettings{}, tan30 + 0.05);
  std::printf("slope: mu = tan + 0.05 moved %.3e m in 2 s\n", stuck);
  EXPECT_LT(stuck, 1e-3);
  // Sliding: s = a t^2 / 2 with a = g (sin - mu cos).
  const double mu = tan30 - 0.2;
  const double a = g * (std::sin(std::numbers::pi / 6.0) - mu * std::cos(std::numbers::pi / 6.0));
  const double slid = testing::slideOnSlope(WorldSettings{}, mu);
  std::printf("slope: mu = tan - 0.2 slid %.4f m, analytic %.4f m\n", slid, 0.5 * a * 4.0);
  EXPECT_NEAR(slid / (0.5 * a * 4.0), 1.0, 0.03);
}

// A plank 10 cm thick sliding at 6 m/s stops where Coulomb friction stops it, flat on the
// ground, under every velocity solver. Its speculative margin (6 m/s x dt = 0.1 m) is wider
// than the plank, which once let the plank's top face into its manifold: it rode on one end
// and sank (3.9 cm under Gauss-Seidel, 1.7 cm under the soft steps, which stopped it at 4.98
// against 6.07 m). Measured now: 6.0663 m (Gauss-Seidel) and 6.1098 m (the soft steps, whose
// sub-steps of dt / 5 put the stop v0 (dt - dt / 5) / 2 = 4 cm further), 0.08 mm of sinking.
TEST(World, PlankSlidingFastStopsWhereCoulombFrictionStopsIt) {
  const double v0 = 6.0, mu = 0.3, g = 9.81, dt = 1.0 / 60.0, half_height = 0.05;
  // Semi-implicit Euler stops a body decelerating at a after v0^2 / (2a) - v0 dt / 2.
  const double stop = v0 * v0 / (2.0 * mu * g) - v0 * dt / 2.0;
  const std::pair<const char*, SolverKind> solvers[] = {
      {"Gauss-Seidel", SolverKind::GaussSeidel},
      {"soft step", SolverKind::SoftStep},
      {"wide soft step", SolverKind::SoftStepWide}};
  for (const auto& [name, kind] : solvers) {
    WorldSettings settings;
    settings.solver.kind = kind;
    World world(settings);
    BodyDesc ground;
    ground.type = BodyType::Static;
    ground.shape = Shape::plane();
    ground.friction = mu;
    world.addBody(ground);
    BodyDesc plank;
    plank.shape = Shape::box(Vec3(1.0, half_height, 0.5));
    plank.position = Vec3(0.0, half_height, 0.0);
    plank.linear_velocity = Vec3(v0, 0.0, 0.0);
    plank.friction = mu;
    const BodyIndex i = world.addBody(plank);
    double lowest = half_height;
    for (int step = 0; step < 300; ++step) {
      world.step(dt);
      lowest = std::min(lowest, world.bodies().position[i].y());
    }
    const double x = world.bodies().position[i].x();
    std::printf("plank, %s: stopped at %.4f m (Coulomb: %.4f m), sank at most %.2e m\n", name, x,
                stop, half_height - lowest);
    EXPECT_NEAR(x / stop, 1.0, 0.01) << name;
    EXPECT_LT(half_height - lowest, 2e-3) << name;
    EXPECT_LT(world.bodies().linear_velocity[i].norm(), 1e-3) << name;
  }
}

/// The shared column of unit cubes (BoxColumn); returns the largest drift of any box after
/// `seconds`, and fills top_height.
double stackDrift(int boxes, int substeps, double seconds, double& top_height) {
  WorldSettings settings;
  settings.solver.velocity_iterations = 10;
  settings.solver.position_iterations = 2;
  settings.substeps = substeps;
  BoxColumn column(settings, std::vector<double>(std::size_t(boxes), 1000.0));
  column.run(seconds);
  top_height = column.topHeight();
  return column.drift().total;
}

// Honest limit: with one step per 1/60 s and 10 iterations, plain PGS propagates the weight of
// a 20-box column too slowly and the column sags and walks; 8 substeps of 1/480 s hold it.
TEST(World, TwentyBoxStackStandsSixtySecondsWithEightSubsteps) {
  double top = 0.0;
  const double drift = stackDrift(20, 8, 60.0, top);
  std::printf("20-box stack after 60 s: largest drift %.4e m, top at %.4f m\n", drift, top);
  EXPECT_LT(drift, 0.01);
}

/// Largest drift of any box from where it started after `seconds` (the floor is body 0).
double driftAfter(World& world, const std::vector<Vec3>& start, double seconds) {
  const int steps = static_cast<int>(std::lround(seconds * 60.0));
  for (int s = 0; s < steps; ++s) world.step(1.0 / 60.0);
  double drift = 0.0;
  for (std::size_t k = 0; k < start.size(); ++k) {
    drift = std::max(drift, (world.bodies().position[k + 1] - start[k]).norm());
  }
  return drift;
}

World worldOnFloor(int substeps) {
  WorldSettings settings;
  settings.substeps = substeps;
  World world(settings);
  BodyDesc floor;
  floor.type = BodyType::Static;
  floor.shape = Shape::box(Vec3(50, 1, 50));
  floor.position = Vec3(0, -1, 0);
  world.addBody(floor);
  return world;
}

// A 15-level pyramid in one vertical plane (120 unit cubes, each level offset by half a box),
// at the default single step per 1/60 s.
TEST(World, FifteenLevelPyramidStandsTenSeconds) {
  World world = worldOnFloor(1);
  std::vector<Vec3> start;
  for (int level = 0; level < 15; ++level) {
    for (int j = 0; j < 15 - level; ++j) {
      BodyDesc box;
      box.shape = Shape::box(Vec3(0.5, 0.5, 0.5));
      box.position = Vec3(j + 0.5 * level - 7.5, 0.5 + level, 0);
      world.addBody(box);
      start.push_back(box.position);
    }
  }
  const double drift = driftAfter(world, start, 10.0);
  std::printf("15-level pyramid (120 boxes) after 10 s: largest drift %.4e m\n", drift);
  EXPECT_LT(drift, 0.02);
}

// A cube 100 times as dense on a light one. Honest limit: this needs 4 substeps; at one step
// per 1/60 s two boxes drift 1.5 cm and three (heavy on top) fall.
TEST(World, HundredToOneMassRatioStackHoldsWithFourSubsteps) {
  World world = worldOnFloor(4);
  std::vector<Vec3> start;
  for (int k = 0; k < 2; ++k) {
    BodyDesc box;
    box.shape = Shape::box(Vec3(0.5, 0.5, 0.5));
    box.position = Vec3(0, 0.5 + k, 0);
    box.density = k == 1 ? 100000.0 : 1000.0;
    world.addBody(box);
    start.push_back(box.position);
  }
  const double drift = driftAfter(world, start, 10.0);
  std::printf("100:1 two-box stack after 10 s: largest drift %.4e m\n", drift);
  EXPECT_LT(drift, 0.01);
}

/// A pile of mixed shapes dropped on a floor; every body's final state, byte for byte.
std::vector<double> pileState(BroadphaseKind broadphase, Integrator integrator) {
  WorldSettings settings;
  settings.broadphase = broadphase;
  settings.integrator = integrator;
  World world(settings);
  addGround(world);
  for (int k = 0; k < 27; ++k) {
    BodyDesc d;
    const int kind = k % 3;
    d.shape = kind == 0   ? Shape::sphere(0.4)
              : kind == 1 ? Shape::box(Vec3(0.4, 0.3, 0.5))
                          : Shape::capsule(0.25, 0.4);
    d.position = Vec3((k % 3) * 1.1 - 1.1, 1.0 + k * 0.9, ((k / 3) % 3) * 1.1 - 1.1);
    d.orientation = about(Vec3(k, 1, 2), 17.0 * k);
    d.angular_velocity = Vec3(0.1 * k, 0, 0);
    world.addBody(d);
  }
  for (int s = 0; s < 240; ++s) world.step(1.0 / 60.0);
  std::vector<double> out;
  for (std::size_t i = 0; i < world.bodies().size(); ++i) {
    const auto& b = world.bodies();
    for (int c = 0; c < 3; ++c) out.push_back(b.position[i][c]);
    for (int c = 0; c < 4; ++c) out.push_back(b.orientation[i].coeffs()[c]);
    for (int c = 0; c < 3; ++c) out.push_back(b.linear_velocity[i][c]);
  }
  return out;
}

TEST(World, SameSceneTwiceIsBitwiseIdentical) {
  const auto a = pileState(BroadphaseKind::SweepAndPrune, Integrator::SemiImplicitEuler);
  const auto b = pileState(BroadphaseKind::SweepAndPrune, Integrator::SemiImplicitEuler);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
  // The pile settled on the ground rather than falling through it.
  for (std::size_t i = 1; i * 10 < a.size(); ++i) EXPECT_GT(a[i * 10 + 1], 0.0);
}

TEST(World, BroadphaseChoiceDoesNotChangeTheResult) {
  const auto reference = pileState(BroadphaseKind::BruteForce, Integrator::VelocityVerlet);
  for (auto kind :
       {BroadphaseKind::SweepAndPrune, BroadphaseKind::UniformGrid, BroadphaseKind::AabbTree}) {
    const auto other = pileState(kind, Integrator::VelocityVerlet);
    EXPECT_EQ(std::memcmp(reference.data(), other.data(), other.size() * sizeof(double)), 0)
        << "broadphase " << int(kind);
  }
}

// Large worlds: everything is double precision, so a scene 100 km from the origin behaves as
// it does at the origin (relative positions agree to well under a micrometre).
TEST(World, SceneFarFromTheOriginMatchesTheSceneAtTheOrigin) {
  auto settle = [](const Vec3& offset) {
    World world;
    BodyDesc floor;
    floor.type = BodyType::Static;
    floor.shape = Shape::box(Vec3(10, 1, 10));
    floor.position = offset + Vec3(0, -1, 0);
    world.addBody(floor);
    for (int k = 0; k < 4; ++k) {
      BodyDesc box;
      box.shape = Shape::box(Vec3(0.5, 0.5, 0.5));
      box.position = offset + Vec3(0.1 * k, 0.6 + 1.05 * k, 0);
      box.orientation = about(Vec3::UnitY(), 10.0 * k);
      world.addBody(box);
    }
    for (int s = 0; s < 120; ++s) world.step(1.0 / 60.0);
    std::vector<Vec3> relative;
    for (std::size_t i = 1; i < world.bodies().size(); ++i) {
      relative.push_back(world.bodies().position[i] - offset);
    }
    return relative;
  };
  const auto near = settle(Vec3::Zero());
  const auto far = settle(Vec3(1e5, 0, -1e5));
  for (std::size_t i = 0; i < near.size(); ++i) EXPECT_LT((near[i] - far[i]).norm(), 1e-6);
}

TEST(World, ThinWallStopsABodyAt200MetresPerSecond) {
  World world;
  world.forces().gravity.setZero();
  BodyDesc wall;
  wall.type = BodyType::Static;
  wall.shape = Shape::box(Vec3(0.05, 5, 5));
  wall.position = Vec3(10, 0, 0);
  world.addBody(wall);
  BodyDesc bullet;
  bullet.shape = Shape::sphere(0.1);
  bullet.linear_velocity = Vec3(200, 0, 0);
  const BodyIndex i = world.addBody(bullet);
  for (int s = 0; s < 60; ++s) {
    world.step(1.0 / 60.0);
    ASSERT_LT(world.bodies().position[i].x(), 10.0 - 0.05) << "step " << s;
  }
  EXPECT_LE(world.bodies().linear_velocity[i].x(), 1e-9);
}

TEST(World, NonFiniteBodyIsQuarantinedAndDoesNotSpread) {
  World world;
  addGround(world);
  BodyDesc d;
  d.shape = Shape::box(Vec3(0.5, 0.5, 0.5));
  d.position = Vec3(0, 0.5, 0);
  const BodyIndex bad = world.addBody(d);
  d.position = Vec3(0, 1.5, 0);
  const BodyIndex above = world.addBody(d);
  for (int s = 0; s < 10; ++s) world.step(1.0 / 60.0);
  world.bodies().angular_velocity[bad] = Vec3(std::nan(""), 0, 0);
  for (int s = 0; s < 60; ++s) world.step(1.0 / 60.0);
  ASSERT_EQ(world.quarantined().size(), 1u);
  EXPECT_EQ(world.quarantined()[0], bad);
  EXPECT_TRUE(world.bodies().position[bad].allFinite());
  EXPECT_TRUE(world.bodies().position[above].allFinite());
  EXPECT_TRUE(world.bodies().orientation[above].coeffs().allFinite());
  EXPECT_NEAR(world.bodies().position[above].y(), 1.5, 0.02);
}

TEST(World, IgnoredPairsNeverTouchAndOtherPairsStill) {
  // Three overlapping spheres in free space (no gravity): 0-1 ignored, 1-2 not.
  World world;
  world.forces().gravity = Vec3::Zero();
  BodyDesc d;
  d.shape = Shape::sphere(0.5);
  for (double x : {0.0, 0.6, 1.2}) {
    d.position = Vec3(x, 0, 0);
    world.addBody(d);
  }
  world.ignoreContactsBetween(1, 0);  // either order
  world.ignoreContactsBetween(0, 1);  // twice is once
  world.step(1.0 / 60.0);
  ASSERT_EQ(world.contacts().size(), 1u);
  EXPECT_EQ(world.contacts()[0].a, 1u);
  EXPECT_EQ(world.contacts()[0].b, 2u);
  // Sphere 0 overlaps 1 and 2 sits farther: nothing pushed it.
  EXPECT_EQ(world.bodies().linear_velocity[0], Vec3::Zero());
  EXPECT_THROW(world.ignoreContactsBetween(0, 0), std::invalid_argument);
  EXPECT_THROW(world.ignoreContactsBetween(0, 3), std::invalid_argument);
}

// The solvers visit a manifold's points in order and the first takes the most load, so every
// manifold the world keeps puts its deepest point first (docs/physics.md, "Contact points
// deepest first"): here a tilted box on the ground and a tilted box on a box, whose points the
// narrowphase finds in corner and polygon order.
TEST(World, FreshManifoldsPutTheirPointsDeepestFirst) {
  World world;
  addGround(world);
  BodyDesc box;
  box.shape = Shape::box(Vec3(0.5, 0.5, 0.5));
  box.orientation = about(Vec3(1, 0, 2), 3.0);
  box.position = Vec3(0, 0.5, 0);
  world.addBody(box);
  box.position = Vec3(5, 0.5, 0);
  box.orientation = Quat::Identity();
  world.addBody(box);
  box.position = Vec3(5.1, 1.49, 0.05);
  box.orientation = about(Vec3(2, 0, -1), 2.0);
  world.addBody(box);
  world.step(1.0 / 60.0);
  int told_apart = 0;  // manifolds with points of different depths
  for (const BodyContact& c : world.contacts()) {
    ASSERT_GE(c.manifold.count, 3) << c.a << "-" << c.b;
    for (int i = 1; i < c.manifold.count; ++i)
      EXPECT_GE(c.manifold.points[i - 1].depth, c.manifold.points[i].depth)
          << c.a << "-" << c.b << " point " << i;
    told_apart += c.manifold.points[0].depth > c.manifold.points[c.manifold.count - 1].depth + 1e-3;
  }
  EXPECT_EQ(world.contacts().size(), 3u);
  EXPECT_EQ(told_apart, 2);  // the two tilted boxes; the upright one rests level
}

}  // namespace
}  // namespace zonesim::physics
