#include "dr/dr_model.h"

#include <gtest/gtest.h>

#include <cmath>

namespace zonesim::dr {
namespace {

constexpr double kPi = 3.14159265358979323846;

Q4 axisAngle(double ax, double ay, double az, double angle) {
  double n = std::sqrt(ax * ax + ay * ay + az * az), s = std::sin(angle / 2) / n;
  return {ax * s, ay * s, az * s, std::cos(angle / 2)};
}

TEST(DrModel, EachOrderMatchesTheMotionItAssumes) {
  // Ballistic motion x(t) = x0 + v0 t + a t^2 / 2, sampled at t = 0.
  State s;
  s.pos = {1, 20, -3};
  s.vel = {2, 5, -1};
  s.acc = {0, -9.81, 0.5};
  for (double t : {0.0, 0.1, 1.0, 3.7}) {
    V3 truth{1 + 2 * t, 20 + 5 * t - 9.81 * t * t / 2, -3 - t + 0.25 * t * t};
    V3 second = predictPosition(s, Order::Second, t);
    EXPECT_NEAR(distance(second, truth), 0, 1e-12) << t;
    V3 v = predictVelocity(s, Order::Second, t);
    EXPECT_NEAR(v.y, 5 - 9.81 * t, 1e-12);
    // First order is exact for constant velocity and off by exactly |a| t^2 / 2 here.
    double a = std::sqrt(9.81 * 9.81 + 0.25);
    EXPECT_NEAR(distance(predictPosition(s, Order::First, t), truth), a * t * t / 2, 1e-9);
    // Static stays put.
    EXPECT_EQ(distance(predictPosition(s, Order::Static, t), s.pos), 0);
  }
}

TEST(DrModel, RotationFollowsAConstantWorldAngularVelocity) {
  State s;
  s.rot = axisAngle(1, 0, 0, 0.3);  // some starting attitude
  s.angvel = {0, 0.8, 0};           // 0.8 rad/s about world y
  for (double t : {0.0, 0.5, 2.0, 10.0}) {
    // Analytic: rotate by 0.8 t about world y after the start rotation.
    Q4 step = axisAngle(0, 1, 0, 0.8 * t);
    Q4 q0 = s.rot;
    Q4 truth{step.w * q0.x + step.x * q0.w + step.y * q0.z - step.z * q0.y,
             step.w * q0.y - step.x * q0.z + step.y * q0.w + step.z * q0.x,
             step.w * q0.z + step.x * q0.y - step.y * q0.x + step.z * q0.w,
             step.w * q0.w - step.x * q0.x - step.y * q0.y - step.z * q0.z};
    EXPECT_LT(angleBetween(predictRotation(s, Spin::Rotating, t), truth), 1e-9) << t;
    // The angle swept from the start is 0.8 t (mod 2 pi, folded to [0, pi]).
    double swept = std::fmod(0.8 * t, 2 * kPi);
    if (swept > kPi) swept = 2 * kPi - swept;
    EXPECT_NEAR(angleBetween(predictRotation(s, Spin::Rotating, t), q0), swept, 1e-9);
    EXPECT_LT(angleBetween(predictRotation(s, Spin::Fixed, t), q0), 1e-12);
  }
}

TEST(DrModel, AngleBetweenTreatsQAndMinusQAsOneRotation) {
  Q4 a = axisAngle(0, 0, 1, 0.2);
  Q4 minus{-a.x, -a.y, -a.z, -a.w};
  EXPECT_NEAR(angleBetween(a, minus), 0, 1e-7);
  EXPECT_NEAR(angleBetween(a, axisAngle(0, 0, 1, 0.5)), 0.3, 1e-12);
}

TEST(DrModel, PositionThresholdOrientationThresholdAndHeartbeat) {
  Thresholds th;
  th.position = 0.5;
  th.orientation_rad = 3 * kPi / 180;
  Model first{Order::First, Spin::Fixed};
  State sent;
  sent.vel = {1, 0, 0};
  const double hb = 5;
  // Moving exactly as predicted: nothing due until the heartbeat.
  EXPECT_EQ(updateDue(sent, first, 2.0, {2, 0, 0}, sent.rot, th, hb), Due::None);
  EXPECT_EQ(updateDue(sent, first, 4.99, {4.99, 0, 0}, sent.rot, th, hb), Due::None);
  EXPECT_EQ(updateDue(sent, first, 5.0, {5, 0, 0}, sent.rot, th, hb), Due::Heartbeat);
  // Turned: 0.4 m off is tolerated, 0.6 m is not.
  EXPECT_EQ(updateDue(sent, first, 2.0, {2, 0, 0.4}, sent.rot, th, hb), Due::None);
  EXPECT_EQ(updateDue(sent, first, 2.0, {2, 0, 0.6}, sent.rot, th, hb), Due::Position);
  // Facing 2 degrees off is tolerated, 4 degrees is not.
  EXPECT_EQ(updateDue(sent, first, 1.0, {1, 0, 0}, axisAngle(0, 1, 0, 2 * kPi / 180), th, hb),
            Due::None);
  EXPECT_EQ(updateDue(sent, first, 1.0, {1, 0, 0}, axisAngle(0, 1, 0, 4 * kPi / 180), th, hb),
            Due::Orientation);
  // A spinning entity under a rotating model needs no update while it spins as predicted.
  State spin;
  spin.angvel = {0, 1, 0};
  Model rotating{Order::Static, Spin::Rotating};
  EXPECT_EQ(updateDue(spin, rotating, 1.5, {}, axisAngle(0, 1, 0, 1.5), th, hb), Due::None);
  EXPECT_EQ(updateDue(spin, {Order::Static, Spin::Fixed}, 1.5, {}, axisAngle(0, 1, 0, 1.5), th, hb),
            Due::Orientation);
}

TEST(DrModel, HeartbeatsOfEntitiesSentTogetherSpreadOverAQuarterPeriod) {
  double lo = 1e9, hi = 0;
  int first_quarter = 0;
  for (std::uint64_t c = 1; c <= 10000; ++c) {
    double p = heartbeatPeriod((std::uint64_t{0xFFFF} << 48) | c, 4.0);
    lo = std::min(lo, p);
    hi = std::max(hi, p);
    first_quarter += p < 3.25;
  }
  EXPECT_GE(lo, 3.0);
  EXPECT_LT(hi, 4.0);
  EXPECT_NEAR(first_quarter / 10000.0, 0.25, 0.03);  // uniform over [3, 4)
}

}  // namespace
}  // namespace zonesim::dr
