#include "topologies/plausibility.h"

#include <gtest/gtest.h>

#include <cmath>

namespace zonesim::topo {
namespace {

constexpr double kDt = 0.05;

MovementLimits limits() {
  MovementLimits l;
  l.max_speed = 5;
  l.max_acceleration = 24;
  l.hit_reach = 1.5;
  return l;
}

TEST(Plausibility, AnHonestWalkIsNeverRejected) {
  PlausibilityChecker c(limits(), kDt);
  // Accelerate at the limit from rest to full speed, then turn round at the limit.
  dr::V3 pos{10, 0, 10}, vel{0, 0, 0};
  double dir = 1;
  for (std::uint64_t t = 0; t < 200; ++t) {
    if (t == 100) dir = -1;
    double target = 5 * dir, dv = std::clamp(target - vel.x, -24 * kDt, 24 * kDt);
    vel.x += dv;
    pos.x += vel.x * kDt;
    EXPECT_EQ(c.checkState(3, t, pos, vel), Violation::None) << "tick " << t;
  }
  EXPECT_EQ(c.rejected(), 0u);
}

TEST(Plausibility, TeleportSpeedAndAccelerationAreCaught) {
  PlausibilityChecker c(limits(), kDt);
  EXPECT_EQ(c.checkState(1, 10, {0, 0, 0}, {5, 0, 0}), Violation::None);
  // 8 m in one tick: 160 m/s of displacement.
  EXPECT_EQ(c.checkState(1, 11, {8, 0, 0}, {5, 0, 0}), Violation::Teleport);
  // Still judged from the last accepted state: one tick later it may be 0.5 m on.
  EXPECT_EQ(c.checkState(1, 12, {0.5, 0, 0}, {5, 0, 0}), Violation::None);
  // A speed hack shows in the claimed velocity.
  EXPECT_EQ(c.checkState(1, 13, {1.25, 0, 0}, {15, 0, 0}), Violation::Speed);
  // Reversing in one tick is 10 m/s in 0.05 s: 200 m/s^2.
  EXPECT_EQ(c.checkState(1, 13, {0.75, 0, 0}, {-5, 0, 0}), Violation::Acceleration);
  EXPECT_EQ(c.checkState(1, 12, {0.5, 0, 0}, {5, 0, 0}), Violation::StaleTick);
  EXPECT_EQ(c.checkState(1, 14, {NAN, 0, 0}, {0, 0, 0}), Violation::NonFinite);
  EXPECT_EQ(c.rejectedOf(1), 5u);
  EXPECT_EQ(c.counts()[std::size_t(Violation::Teleport)], 1u);
  EXPECT_EQ(c.counts()[std::size_t(Violation::Speed)], 1u);
  EXPECT_EQ(c.counts()[std::size_t(Violation::Acceleration)], 1u);
}

TEST(Plausibility, AFirstStateTooFastIsRejectedAndNotRemembered) {
  PlausibilityChecker c(limits(), kDt);
  EXPECT_EQ(c.checkState(2, 0, {30, 0, 0}, {50, 0, 0}), Violation::Speed);
  // The next honest state is the first reference: no teleport from the rejected one.
  EXPECT_EQ(c.checkState(2, 1, {0, 0, 0}, {0, 0, 0}), Violation::None);
  EXPECT_EQ(c.rejectedOf(2), 1u);
  EXPECT_EQ(c.rejectedOf(7), 0u);
}

TEST(Plausibility, APlayerWhoseNewestStateWasRejectedIsDistrusted) {
  PlausibilityChecker c(limits(), kDt);
  EXPECT_EQ(c.checkState(5, 1, {0, 0, 0}, {0, 0, 0}), Violation::None);
  EXPECT_FALSE(c.distrusts(5));
  EXPECT_EQ(c.checkState(5, 2, {9, 0, 0}, {0, 0, 0}), Violation::Teleport);
  EXPECT_TRUE(c.distrusts(5));
  EXPECT_EQ(c.checkState(5, 1, {0, 0, 0}, {0, 0, 0}), Violation::StaleTick);
  EXPECT_TRUE(c.distrusts(5));  // a late duplicate does not restore trust
  EXPECT_EQ(c.checkState(5, 3, {0.1, 0, 0}, {0, 0, 0}), Violation::None);
  EXPECT_FALSE(c.distrusts(5));
}

TEST(Plausibility, HitsBeyondReachAreRejected) {
  PlausibilityChecker c(limits(), kDt);
  EXPECT_EQ(c.checkHit(4, {0, 0, 0}, {1.0, 0, 1.0}), Violation::None);  // 1.41 m
  EXPECT_EQ(c.checkHit(4, {0, 0, 0}, {20, 0, 0}), Violation::HitOutOfReach);
  EXPECT_EQ(c.checkHit(4, {0, 0, 0}, {0, 0, INFINITY}), Violation::NonFinite);
  EXPECT_EQ(c.rejectedOf(4), 2u);
}

TEST(Plausibility, WithoutProbationATeleporterStaysFrozenWhereItWasBelieved) {
  PlausibilityChecker c(limits(), kDt);
  EXPECT_EQ(c.checkState(6, 0, {10, 0, 10}, {0, 0, 0}), Violation::None);
  // ... until it could have walked there: 20 m at 5 m/s, 80 ticks.
  for (std::uint64_t t = 1; t < 80; ++t)
    EXPECT_EQ(c.checkState(6, t, {30, 0, 10}, {0, 0, 0}), Violation::Teleport) << t;
  EXPECT_EQ(c.reanchoredOf(6), 0u);
}

TEST(Plausibility, AfterItsProbationATeleporterIsShownWhereItNowIs) {
  MovementLimits l = limits();
  l.probation_ticks = 20;
  PlausibilityChecker c(l, kDt);
  EXPECT_EQ(c.checkState(6, 0, {10, 0, 10}, {0, 0, 0}), Violation::None);
  // It jumps 8 m at tick 1 and walks on from there at 2 m/s: every state is rejected against
  // the last one believed, until 20 ticks of them agree with each other.
  auto at = [](std::uint64_t t) { return dr::V3{18 + 0.1 * double(t - 1), 0, 10}; };
  for (std::uint64_t t = 1; t <= 20; ++t)
    EXPECT_EQ(c.checkState(6, t, at(t), {2, 0, 0}), Violation::Teleport) << t;
  EXPECT_TRUE(c.distrusts(6));
  EXPECT_EQ(c.checkState(6, 21, at(21), {2, 0, 0}), Violation::None);
  EXPECT_FALSE(c.distrusts(6));
  EXPECT_EQ(c.reanchoredOf(6), 1u);
  EXPECT_EQ(c.rejectedOf(6), 20u);
  // From the new anchor it is judged as anyone: the next step is fine, a jump back is not.
  EXPECT_EQ(c.checkState(6, 22, at(22), {2, 0, 0}), Violation::None);
  EXPECT_EQ(c.checkState(6, 23, {10, 0, 10}, {2, 0, 0}), Violation::Teleport);
}

TEST(Plausibility, AProbationRestartsOnEveryNewJumpAndNeverForgivesSpeed) {
  MovementLimits l = limits();
  l.probation_ticks = 20;
  PlausibilityChecker c(l, kDt);
  EXPECT_EQ(c.checkState(7, 0, {10, 0, 10}, {0, 0, 0}), Violation::None);
  // Jumping 8 m every 10 ticks: its claims never agree for 20 ticks. (From tick 40 on, the
  // first place is within walking distance of where it was believed at tick 0.)
  for (std::uint64_t t = 1; t < 40; ++t) {
    double x = 18 + 8 * double(t / 10 % 2);
    EXPECT_NE(c.checkState(7, t, {x, 0, 10}, {0, 0, 0}), Violation::None) << t;
  }
  // Three times full speed, smoothly: each claim agrees with the last, but none is possible.
  for (std::uint64_t t = 200; t < 300; ++t)
    EXPECT_EQ(c.checkState(7, t, {0.75 * double(t - 200), 0, 30}, {15, 0, 0}), Violation::Speed);
  EXPECT_EQ(c.reanchoredOf(7), 0u);
  // A late duplicate neither restarts nor advances it.
  EXPECT_EQ(c.checkState(8, 0, {0, 0, 0}, {0, 0, 0}), Violation::None);
  for (std::uint64_t t = 1; t <= 20; ++t) {
    EXPECT_EQ(c.checkState(8, t, {9, 0, 0}, {0, 0, 0}), Violation::Teleport) << t;
    EXPECT_EQ(c.checkState(8, t, {9, 0, 0}, {0, 0, 0}), Violation::Teleport) << t;
  }
  EXPECT_EQ(c.checkState(8, 21, {9, 0, 0}, {0, 0, 0}), Violation::None);
}

TEST(Plausibility, ViolationsHaveNames) {
  EXPECT_STREQ(violationName(Violation::Teleport), "teleport");
  EXPECT_STREQ(violationName(Violation::HitOutOfReach), "hit_out_of_reach");
}

}  // namespace
}  // namespace zonesim::topo
