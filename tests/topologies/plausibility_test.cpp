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

TEST(Plausibility, ViolationsHaveNames) {
  EXPECT_STREQ(violationName(Violation::Teleport), "teleport");
  EXPECT_STREQ(violationName(Violation::HitOutOfReach), "hit_out_of_reach");
}

}  // namespace
}  // namespace zonesim::topo
