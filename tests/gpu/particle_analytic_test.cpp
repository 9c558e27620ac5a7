// Both backends against closed-form motion: a vertical throw (apex v0^2/2g, landing at 2 v0/g,
// rebound apex e^2 v0^2/2g) and a drop under linear drag (v(t) = -(g/k)(1 - e^-kt)).

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/gpu/device_fixture.h"

namespace zonesim::gpu {
namespace {

constexpr double kG = 9.81;

class Analytic : public ::testing::TestWithParam<Backend> {};

// One particle at origin moving at velocity exactly (cone half-angle 0).
void emitOne(ParticleSystem& system, Vec3d origin, Vec3d direction, double speed, double lifetime) {
  Pcg32 rng(1, 1);
  EmitSpec spec{origin, direction, 0.0, speed, lifetime};
  ASSERT_EQ(system.emit(spec, 1, rng), 1u);
}

TEST_P(Analytic, VerticalThrowReturnsAtTheAnalyticTimeAndHeight) {
  ZS_REQUIRE_BACKEND(GetParam());
  const double v0 = 10.0, dt = 1e-3, e = 0.5;
  ParticleSystem system = test::makeSystem(GetParam());
  emitOne(system, {0, 0, 0}, {0, 1, 0}, v0, 100.0);

  std::vector<Vec3d> pos, vel;
  double apex = 0, rebound_apex = 0, landing_time = -1;
  for (int n = 1; n <= 4000; ++n) {
    double vy_before = 0;
    system.readVelocities(vel);
    vy_before = vel[0].y;
    system.step(dt, {0, -kG, 0}, 0.0, e);
    system.readPositions(pos);
    system.readVelocities(vel);
    ASSERT_GE(pos[0].y, 0.0) << "below the ground at step " << n;
    if (landing_time < 0) {
      apex = std::max(apex, pos[0].y);
      if (vy_before < 0 && vel[0].y > 0) landing_time = n * dt;
    } else {
      rebound_apex = std::max(rebound_apex, pos[0].y);
    }
    EXPECT_DOUBLE_EQ(pos[0].x, 0.0);
    EXPECT_DOUBLE_EQ(pos[0].z, 0.0);
  }
  // Semi-implicit Euler peaks v0 dt / 2 below v0^2/2g (the discrete sum of the fall) and lands
  // within a step of 2 v0 / g; the bounce step is the one that contains the impact. Tolerances
  // are twice those first-order terms; float rounding (~1e-5 m over 2,000 steps) is far below.
  const double h = v0 * v0 / (2 * kG);
  EXPECT_NEAR(apex, h, v0 * dt) << "apex";
  EXPECT_NEAR(landing_time, 2 * v0 / kG, 2 * dt) << "landing time";
  // The rebound leaves at e times the impact speed, so it peaks at e^2 h.
  EXPECT_NEAR(rebound_apex, e * e * h, 2 * v0 * dt) << "rebound apex";
}

TEST_P(Analytic, DragDropFollowsTheExponentialApproachToTerminalVelocity) {
  ZS_REQUIRE_BACKEND(GetParam());
  const double k = 0.5, dt = 1.0 / 60.0;
  ParticleSystem system = test::makeSystem(GetParam());
  emitOne(system, {3, 1000, -2}, {0, 1, 0}, 0.0, 100.0);

  std::vector<Vec3d> vel;
  const int steps = 240;
  for (int n = 0; n < steps; ++n) system.step(dt, {0, -kG, 0}, k, 0.5);
  system.readVelocities(vel);
  const double t = steps * dt;
  const double exact = -(kG / k) * (1 - std::exp(-k * t));
  // Explicit drag gives (1 - k dt)^n for e^-kt: a first-order error of g e^-kt k t dt / 2
  // (0.022 m/s here); allow twice that.
  EXPECT_NEAR(vel[0].y, exact, kG * std::exp(-k * t) * k * t * dt) << "at t = " << t;

  // The discrete scheme's fixed point is exactly the terminal velocity -g/k. In float, v stops
  // moving once (g - k v) dt is under half an ulp of v: within ulp(19.6) / (2 k dt) = 1.1e-4.
  for (int n = 0; n < 1800; ++n) system.step(dt, {0, -kG, 0}, k, 0.5);
  system.readVelocities(vel);
  EXPECT_NEAR(vel[0].y, -kG / k, 3e-4);
  EXPECT_DOUBLE_EQ(vel[0].x, 0.0);
}

TEST_P(Analytic, ProjectileWithoutDragKeepsItsHorizontalVelocityThroughABounce) {
  ZS_REQUIRE_BACKEND(GetParam());
  const double dt = 1.0 / 120.0;
  ParticleSystem system = test::makeSystem(GetParam());
  emitOne(system, {0, 2, 0}, {3, 4, 0}, 5.0, 100.0);  // vx = 3, vy = 4
  // Two seconds: it lands after about 1.17 s and bounces, which must not touch x.
  std::vector<Vec3d> pos, vel;
  int bounces = 0;
  for (int n = 0; n < 240; ++n) {
    system.readVelocities(vel);
    double vy_before = vel[0].y;
    system.step(dt, {0, -kG, 0}, 0.0, 0.8);
    system.readVelocities(vel);
    if (vy_before < 0 && vel[0].y > 0) ++bounces;
  }
  system.readPositions(pos);
  EXPECT_EQ(bounces, 1);
  EXPECT_NEAR(vel[0].x, 3.0, 1e-5);
  EXPECT_NEAR(pos[0].x, 6.0, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(Backends, Analytic, ::testing::Values(Backend::Cpu, Backend::OpenCl),
                         [](const auto& info) { return std::string(backendName(info.param)); });

}  // namespace
}  // namespace zonesim::gpu
