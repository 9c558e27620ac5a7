// Level of detail in time (physics/step_lod.h): far islands step every k-th call by the time
// they skipped, near bodies are not changed by them, and a near body meeting a held one moves
// it instead of passing through.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "physics/world.h"

namespace zonesim::physics {
namespace {

constexpr double kDt = 1.0 / 60.0;

World groundWorld(const WorldSettings& settings = {}) {
  World world(settings);
  BodyDesc ground;
  ground.type = BodyType::Static;
  ground.shape = Shape::plane();
  world.addBody(ground);
  return world;
}

BodyIndex addBall(World& world, const Vec3& at, const Vec3& velocity) {
  BodyDesc ball;
  ball.shape = Shape::sphere(0.5);
  ball.position = at;
  ball.linear_velocity = velocity;
  return world.addBody(ball);
}

BodyIndex addBox(World& world, const Vec3& at) {
  BodyDesc box;
  box.shape = Shape::box(Vec3(0.5, 0.5, 0.5));
  box.position = at;
  return world.addBody(box);
}

bool sameState(const World& x, BodyIndex i, const World& y, BodyIndex k) {
  const BodyStorage &a = x.bodies(), &b = y.bodies();
  return a.position[i] == b.position[k] && a.linear_velocity[i] == b.linear_velocity[k] &&
         a.orientation[i].coeffs() == b.orientation[k].coeffs() &&
         a.angular_velocity[i] == b.angular_velocity[k];
}

// Steps `lod` `calls` times; every `every` calls its body a must equal body b of `reference`
// stepped once by dt, then by every x dt at each of those calls.
void expectLongSteps(World& lod, BodyIndex a, World& reference, BodyIndex b, int every,
                     int calls) {
  reference.step(kDt);
  for (int call = 0; call < calls; ++call) {
    lod.step(kDt);
    if (call == 0 || call % every != 0) {
      EXPECT_EQ(lod.stepLod().lag(a), call % every) << "call " << call;
      continue;
    }
    reference.step(every * kDt);
    ASSERT_TRUE(sameState(lod, a, reference, b)) << "call " << call;
  }
}

TEST(StepLod, FarBallStepsByTheTimeItSkipped) {
  // Period 4 from the first call: it steps at calls 0, 4, 8, ... by dt, then 4 dt each time.
  World lod = groundWorld(), reference = groundWorld();
  const BodyIndex a = addBall(lod, Vec3(0, 3, 0), Vec3(2, 4, 0));
  const BodyIndex b = addBall(reference, Vec3(0, 3, 0), Vec3(2, 4, 0));
  lod.setStepPeriod(a, 4);
  expectLongSteps(lod, a, reference, b, 4, 41);
  // The ball bounced on the way: the contact steps are the long ones too.
  EXPECT_EQ(lod.stepLod().bodiesStepped(), 11u);
  EXPECT_EQ(lod.stepLod().bodiesHeld(), 30u);
}

TEST(StepLod, TheLongestStepCutsThePeriod) {
  // Steps of at most 2.5 ticks: period 8 is cut to 2, so the ball steps dt, then 2 dt each time.
  WorldSettings settings;
  settings.lod_longest_step = 2.5 * kDt;
  World lod = groundWorld(settings), reference = groundWorld();
  const BodyIndex a = addBall(lod, Vec3(0, 3, 0), Vec3(2, 4, 0));
  const BodyIndex b = addBall(reference, Vec3(0, 3, 0), Vec3(2, 4, 0));
  lod.setStepPeriod(a, 8);
  expectLongSteps(lod, a, reference, b, 2, 21);
}

TEST(StepLod, NearBodiesAreNotChangedByAHeldFarPile) {
  // A near ball bouncing beside a far stack that steps every 4 calls moves bit for bit as in a
  // world without the stack.
  World lod = groundWorld(), alone = groundWorld();
  const BodyIndex near = addBall(lod, Vec3(0, 2, 0), Vec3(0.5, 0, 0));
  const BodyIndex ref = addBall(alone, Vec3(0, 2, 0), Vec3(0.5, 0, 0));
  std::vector<BodyIndex> stack;
  for (int level = 0; level < 3; ++level) stack.push_back(addBox(lod, Vec3(50, 0.5 + level, 0)));
  for (BodyIndex i : stack) lod.setStepPeriod(i, 4);
  double drift = 0, end_drift = 0;
  for (int call = 0; call < 600; ++call) {
    lod.step(kDt);
    alone.step(kDt);
    ASSERT_TRUE(sameState(lod, near, alone, ref)) << "call " << call;
    end_drift = 0;
    for (int level = 0; level < 3; ++level) {
      const Vec3 start(50, 0.5 + level, 0);
      end_drift = std::max(end_drift, (lod.bodies().position[stack[level]] - start).norm());
    }
    drift = std::max(drift, end_drift);
  }
  // The same stack stepped every call, for scale.
  World full = groundWorld();
  for (int level = 0; level < 3; ++level) addBox(full, Vec3(50, 0.5 + level, 0));
  double full_drift = 0;
  for (int call = 0; call < 600; ++call) {
    full.step(kDt);
    for (int level = 0; level < 3; ++level) {
      const Vec3 start(50, 0.5 + level, 0);
      full_drift = std::max(full_drift, (full.bodies().position[1 + level] - start).norm());
    }
  }
  std::printf(
      "3-box stack for 10 s: drift %.4f m stepped every 4 calls (15 Hz), %.4f m at "
      "the end, %.4f m every call\n",
      drift, end_drift, full_drift);
  // Gauss-Seidel at 1/15 s: the widest drift is the first long steps' settling of boxes that
  // start touching; then the stack wanders a little sideways. With the contact points deepest
  // first 2.2 cm widest and 1.4 cm at the end (in the narrowphase's polygon order: 1.8 and
  // 0.6 cm).
  EXPECT_LT(drift, 0.03);
  EXPECT_LT(end_drift, 0.02);
}

TEST(StepLod, NearBallMeetingAHeldBoxPushesIt) {
  // The box waits for its 8-call step when the ball reaches it: the ball's contact stops it
  // (the held box stands as an immovable obstacle), the box joins its island and steps with
  // it from the next call.
  World world = groundWorld();
  const BodyIndex ball = addBall(world, Vec3(0, 0.5, 0), Vec3(6, 0, 0));
  const BodyIndex box = addBox(world, Vec3(2.5, 0.5, 0));
  world.setStepPeriod(box, 8);
  double deepest = 0;
  bool joined = false;
  for (int call = 0; call < 120; ++call) {
    world.step(kDt);
    const BodyStorage& s = world.bodies();
    const double gap = (s.position[box].x() - 0.5) - (s.position[ball].x() + 0.5);
    deepest = std::min(deepest, gap);
    joined |= world.stepLod().lag(box) == 0 && call % 8 != 0 && s.position[box].x() > 2.5001;
  }
  std::printf("ball into a held box: deepest overlap %.4f m, box at x = %.3f\n", -deepest,
              world.bodies().position[box].x());
  EXPECT_GT(deepest, -0.02);
  EXPECT_TRUE(joined);
  EXPECT_GT(world.bodies().position[box].x(), 2.6);
}

}  // namespace
}  // namespace zonesim::physics
