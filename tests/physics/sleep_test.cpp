#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "physics/world.h"

namespace zonesim::physics {
namespace {

World sleepyWorld() {
  WorldSettings settings;
  settings.sleep.enabled = true;
  World world(settings);
  BodyDesc ground;
  ground.type = BodyType::Static;
  ground.shape = Shape::plane();
  world.addBody(ground);
  return world;
}

TEST(Sleep, BouncyBallsComeToRestAtThirtyHertz) {
  // Restitution 0.5 at a 30 Hz tick: a ball that falls just past the contact margin arrives
  // with 2 g dt = 0.65 m/s, above the 0.5 m/s bounce threshold, and used to hop 1.1 cm every
  // 3 ticks for ever. Dropped from 15 m, one at rest and one rolling must settle on y = r.
  const double dt = 1.0 / 30.0, r = 0.5;
  World world = sleepyWorld();
  BodyDesc ball;
  ball.shape = Shape::sphere(r);
  ball.restitution = 0.5;
  ball.position = Vec3(0, 15, 0);
  const BodyIndex still = world.addBody(ball);
  ball.position = Vec3(0, 15, 10);
  ball.linear_velocity = Vec3(1.7, 0, 0);
  const BodyIndex rolling = world.addBody(ball);
  double low = 1e9, high = -1e9;
  for (int step = 0; step < 600; ++step) {
    world.step(dt);
    if (step < 500) continue;
    for (BodyIndex i : {still, rolling}) {
      low = std::min(low, world.bodies().position[i].y());
      high = std::max(high, world.bodies().position[i].y());
    }
  }
  std::printf("after 16.7 s at 30 Hz: heights %.9f..%.9f m (radius %.1f), still ball asleep %d\n",
              low, high, r, int(world.asleep(still)));
  EXPECT_NEAR(low, r, 1e-6);
  EXPECT_NEAR(high, r, 1e-6);
  EXPECT_TRUE(world.asleep(still));
}

TEST(Sleep, RestingBoxFallsAsleepAndHoldsStill) {
  World world = sleepyWorld();
  BodyDesc box;
  box.shape = Shape::box(Vec3(0.5, 0.5, 0.5));
  box.position = Vec3(0, 1.0, 0);
  const BodyIndex i = world.addBody(box);
  for (int s = 0; s < 180; ++s) world.step(1.0 / 60.0);
  ASSERT_TRUE(world.asleep(i));
  EXPECT_NEAR(world.bodies().position[i].y(), 0.5, 0.01);
  const Vec3 before = world.bodies().position[i];
  for (int s = 0; s < 120; ++s) world.step(1.0 / 60.0);
  EXPECT_EQ(std::memcmp(before.data(), world.bodies().position[i].data(), sizeof(Vec3)), 0);
  EXPECT_EQ(world.sleepingCount(), 1u);
}

TEST(Sleep, SleepingStackWakesWhenHitAndStillHoldsTheBall) {
  World world = sleepyWorld();
  std::vector<BodyIndex> stack;
  for (int k = 0; k < 3; ++k) {
    BodyDesc box;
    box.shape = Shape::box(Vec3(0.5, 0.5, 0.5));
    box.position = Vec3(0, 0.5 + k, 0);
    stack.push_back(world.addBody(box));
  }
  for (int s = 0; s < 120; ++s) world.step(1.0 / 60.0);
  for (BodyIndex b : stack) ASSERT_TRUE(world.asleep(b));
  BodyDesc ball;
  ball.shape = Shape::sphere(0.3);
  ball.position = Vec3(0.1, 5.0, 0);
  const BodyIndex i = world.addBody(ball);
  bool stack_woke = false;
  for (int s = 0; s < 120; ++s) {
    world.step(1.0 / 60.0);
    for (BodyIndex b : stack) stack_woke = stack_woke || !world.asleep(b);
  }
  EXPECT_TRUE(stack_woke);
  // The ball rests on the top box rather than having fallen through a sleeping stack.
  EXPECT_GT(world.bodies().position[i].y(), 3.0 + 0.3 - 0.05);
}

TEST(Sleep, AppliedForceWakesASleepingBody) {
  World world = sleepyWorld();
  BodyDesc box;
  box.shape = Shape::box(Vec3(0.5, 0.5, 0.5));
  box.position = Vec3(0, 0.5, 0);
  const BodyIndex i = world.addBody(box);
  for (int s = 0; s < 120; ++s) world.step(1.0 / 60.0);
  ASSERT_TRUE(world.asleep(i));
  world.applyForce(i, Vec3(0, 1e6, 0));
  EXPECT_FALSE(world.asleep(i));
  world.step(1.0 / 60.0);
  EXPECT_GT(world.bodies().linear_velocity[i].y(), 1.0);
}

}  // namespace
}  // namespace zonesim::physics
