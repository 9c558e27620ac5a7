// What a world carries from one step to the next (sleep, and the impulses that warm-start the
// solver) can be taken out and put into a new world: a world rebuilt mid-run steps on bit for
// bit, and an island steps the same beside other islands or alone. Zones rely on both to solve
// contacts across borders exactly (zone_node/systems/body_islands.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "physics/world.h"

namespace zonesim::physics {
namespace {

constexpr double kDt = 1.0 / 60.0;

WorldSettings sleepy() {
  WorldSettings s;
  s.sleep.enabled = true;
  return s;
}

BodyDesc floorBox() {
  BodyDesc d;
  d.type = BodyType::Static;
  d.shape = Shape::box(Vec3(50, 1, 50));
  d.position = Vec3(0, -1, 0);
  return d;
}

/// A column of boxes at x and a sphere dropped off-centre onto it from high up: the column
/// sleeps, then the sphere wakes it and knocks it about.
std::vector<BodyDesc> columnAndDrop(double x, int boxes) {
  std::vector<BodyDesc> out;
  for (int k = 0; k < boxes; ++k) {
    BodyDesc b;
    b.shape = Shape::box(Vec3(0.5, 0.5, 0.5));
    b.position = Vec3(x, 0.5 + k, 0);
    b.friction = 0.6;
    out.push_back(b);
  }
  BodyDesc ball;
  ball.shape = Shape::sphere(0.3);
  ball.position = Vec3(x + 0.2, boxes + 80.0, 0.1);  // lands after about 4 s
  ball.density = 5;
  out.push_back(ball);
  return out;
}

/// A world of the floor and the given bodies, in order.
World worldOf(const WorldSettings& settings, const std::vector<BodyDesc>& bodies) {
  World w(settings);
  w.addBody(floorBox());
  for (const BodyDesc& d : bodies) w.addBody(d);
  return w;
}

void expectSameBodies(const World& a, BodyIndex first_a, const World& b, BodyIndex first_b,
                      std::size_t count) {
  for (std::size_t k = 0; k < count; ++k) {
    const BodyIndex i = BodyIndex(first_a + k), j = BodyIndex(first_b + k);
    EXPECT_EQ(a.bodies().position[i], b.bodies().position[j]) << "body " << k;
    EXPECT_EQ(a.bodies().linear_velocity[i], b.bodies().linear_velocity[j]) << "body " << k;
    EXPECT_EQ(a.bodies().orientation[i].coeffs(), b.bodies().orientation[j].coeffs())
        << "body " << k;
    EXPECT_EQ(a.asleep(i), b.asleep(j)) << "body " << k;
  }
}

TEST(WorldCarry, AWorldRebuiltMidRunWithItsSleepAndWarmStartsStepsOnBitForBit) {
  const std::vector<BodyDesc> bodies = columnAndDrop(0, 6);
  World whole = worldOf(sleepy(), bodies);
  World first = worldOf(sleepy(), bodies);
  // Rebuilt at 180 steps: the column is asleep (the ball is still falling); at 300 it is awake
  // again after the ball hit it.
  std::size_t slept = 0;
  for (int s = 0; s < 180; ++s) {
    whole.step(kDt);
    first.step(kDt);
  }
  for (std::size_t k = 1; k <= 6; ++k) slept += first.asleep(BodyIndex(k));
  EXPECT_EQ(slept, 6u) << "the column sleeps when the world is rebuilt";

  std::vector<BodyDesc> now = bodies;
  for (std::size_t k = 0; k < now.size(); ++k) {
    const BodyIndex i = BodyIndex(k + 1);
    now[k].position = first.bodies().position[i];
    now[k].linear_velocity = first.bodies().linear_velocity[i];
    now[k].angular_velocity = first.bodies().angular_velocity[i];
  }
  World rebuilt = worldOf(sleepy(), now);
  for (std::size_t k = 0; k < now.size(); ++k) {
    const BodyIndex i = BodyIndex(k + 1);
    rebuilt.bodies().orientation[i] = first.bodies().orientation[i];  // exactly, not normalised
    rebuilt.setSleepState(i, first.sleepState(i));
  }
  WarmStarts warm;
  first.warmStarts(warm);
  EXPECT_GE(warm.contacts.size(), 6u)
      << "the sleeping column's contacts are kept for its warm start";
  rebuilt.setWarmStarts(warm);
  std::size_t woke = 0;
  for (int s = 180; s < 450; ++s) {
    whole.step(kDt);
    rebuilt.step(kDt);
    if (s == 260)
      for (std::size_t k = 1; k <= 6; ++k) woke += !whole.asleep(BodyIndex(k));
  }
  EXPECT_GT(woke, 0u) << "the ball woke the column after the rebuild";
  expectSameBodies(whole, 1, rebuilt, 1, bodies.size());
}

TEST(WorldCarry, AnIslandStepsTheSameBesideOthersAsAlone) {
  // Island A, a column, falls asleep and is pushed awake at step 300. Alone, its world is not
  // stepped while it sleeps (as a zone skips a world with nothing awake); beside island B,
  // which keeps rolling, the world steps all along. A must wake with the same warm starts.
  std::vector<BodyDesc> a = columnAndDrop(0, 5);
  a.pop_back();  // no ball: the push wakes it
  std::vector<BodyDesc> both = a;
  for (const BodyDesc& d : columnAndDrop(10, 3)) both.push_back(d);
  BodyDesc roller;
  roller.shape = Shape::sphere(0.5);
  roller.position = Vec3(-20, 0.5, 5);
  roller.linear_velocity = Vec3(0, 0, 3);
  both.push_back(roller);
  World alone = worldOf(sleepy(), a);
  World together = worldOf(sleepy(), both);
  std::size_t skipped = 0;
  for (int s = 0; s < 500; ++s) {
    if (s == 300) {
      for (World* w : {&alone, &together}) w->applyForce(BodyIndex(a.size()), Vec3(400, 0, 150));
    }
    bool awake = false;
    for (std::size_t k = 1; k <= a.size(); ++k) awake |= !alone.asleep(BodyIndex(k));
    if (awake) {
      alone.step(kDt);
    } else {
      ++skipped;
    }
    together.step(kDt);
  }
  EXPECT_GT(skipped, 50u) << "island A slept while B moved";
  expectSameBodies(alone, 1, together, 1, a.size());
}

TEST(WorldCarry, AConjugateGradientIslandStepsTheSameBesideOthersAsAlone) {
  // The conjugate-gradient solver's step length and restarts are per group of linked contacts:
  // a column knocked about by a ball ends bit for bit the same beside a second column and ball
  // (whose gradients a global step length mixed into its own) as alone.
  WorldSettings cg;
  cg.solver.kind = SolverKind::ConjugateGradient;
  const std::vector<BodyDesc> a = columnAndDrop(0, 5);
  std::vector<BodyDesc> both = a;
  for (const BodyDesc& d : columnAndDrop(10, 4)) both.push_back(d);
  World alone = worldOf(cg, a);
  World together = worldOf(cg, both);
  for (int s = 0; s < 400; ++s) {
    alone.step(kDt);
    together.step(kDt);
  }
  // The ball landed (about 4 s) and shook the column (by 2.5 mm): it had contacts to solve.
  double moved = 0;
  for (std::size_t k = 1; k < a.size(); ++k)
    moved = std::max(moved, (alone.bodies().position[BodyIndex(k)] - a[k - 1].position).norm());
  EXPECT_GT(moved, 1e-3);
  expectSameBodies(alone, 1, together, 1, a.size());
}

}  // namespace
}  // namespace zonesim::physics
