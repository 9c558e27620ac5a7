#include "physics/integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

namespace zonesim::physics {
namespace {

constexpr Integrator kAll[] = {Integrator::ExplicitEuler,  Integrator::SemiImplicitEuler,
                               Integrator::PositionVerlet, Integrator::VelocityVerlet,
                               Integrator::Rk2Midpoint,    Integrator::Rk4};

/// One free particle driven by a force model, integrated with one scheme.
struct Particle {
  Particle(const Vec3& x0, const Vec3& v0) : x(x0), v(v0) {}

  Vec3 x, v, x_out = Vec3::Zero(), v_out = Vec3::Zero(), x_prev = Vec3::Zero();
  double inv_mass = 1.0;
  bool started = false;
  LinearIntegrator integrator;

  void step(Integrator kind, const ForceModel& f, double dt) {
    LinearStateView view{{&x, 1},     {&v, 1},      {&inv_mass, 1}, {&x_out, 1},
                         {&v_out, 1}, {&x_prev, 1}, started,        {}};
    integrator.step(kind, f, view, dt);
    started = true;
    x = x_out;
    v = v_out;
  }
};

ForceModel oscillator(double stiffness) {
  ForceModel f;
  f.gravity.setZero();
  f.springs.push_back(Spring{0, kWorldAnchor, Vec3::Zero(), stiffness, 0.0, 0.0});
  return f;
}

/// Position error at time t of the unit oscillator x'' = -x from x = 1, v = 0.
double oscillatorError(Integrator kind, double dt, double t) {
  const ForceModel f = oscillator(1.0);
  Particle p(Vec3(1, 0, 0), Vec3::Zero());
  const int steps = static_cast<int>(std::lround(t / dt));
  for (int i = 0; i < steps; ++i) p.step(kind, f, dt);
  return (p.x - Vec3(std::cos(t), 0, 0)).norm();
}

TEST(Integrator, OscillatorConvergenceOrderMatchesTheory) {
  for (Integrator kind : kAll) {
    const double e1 = oscillatorError(kind, 0.01, 2.0);
    const double e2 = oscillatorError(kind, 0.005, 2.0);
    const double order = std::log2(e1 / e2);
    std::printf("oscillator order %d: %.3f (errors %.3e, %.3e)\n", int(kind), order, e1, e2);
    EXPECT_NEAR(order, integratorOrder(kind), 0.25) << "integrator " << int(kind);
  }
}

TEST(Integrator, ProjectileWithoutDragMatchesParabola) {
  // Constant acceleration: the second-order and higher schemes are exact; the Euler schemes
  // are off by exactly -/+ g t dt / 2 in height.
  ForceModel f;
  const double dt = 0.01, t = 2.0, g = 9.81;
  const Vec3 v0(3.0, 12.0, -1.0);
  const Vec3 exact = v0 * t + 0.5 * f.gravity * t * t;
  for (Integrator kind : kAll) {
    Particle p(Vec3::Zero(), v0);
    for (int i = 0; i < 200; ++i) p.step(kind, f, dt);
    double expected_dy = 0.0;
    if (kind == Integrator::ExplicitEuler) expected_dy = 0.5 * g * t * dt;
    if (kind == Integrator::SemiImplicitEuler) expected_dy = -0.5 * g * t * dt;
    EXPECT_NEAR(p.x.y() - exact.y(), expected_dy, 1e-9) << "integrator " << int(kind);
    EXPECT_NEAR(p.x.x(), exact.x(), 1e-9);
    EXPECT_NEAR(p.x.z(), exact.z(), 1e-9);
  }
}

/// Error in position at t of a projectile with linear drag F = -k v against the closed form.
double dragError(Integrator kind, double dt) {
  ForceModel f;
  f.linear_drag = 0.5;
  const double mass = 2.0, tau = mass / f.linear_drag, t = 3.0;
  const Vec3 v0(20.0, 15.0, 5.0);
  const Vec3 v_inf = f.gravity * tau;
  const Vec3 exact = v_inf * t + tau * (v0 - v_inf) * (1.0 - std::exp(-t / tau));
  Particle p(Vec3::Zero(), v0);
  p.inv_mass = 1.0 / mass;
  const int steps = static_cast<int>(std::lround(t / dt));
  for (int i = 0; i < steps; ++i) p.step(kind, f, dt);
  return (p.x - exact).norm();
}

TEST(Integrator, ProjectileWithLinearDragConvergesToClosedForm) {
  for (Integrator kind : kAll) {
    const double e1 = dragError(kind, 0.02);
    const double e2 = dragError(kind, 0.01);
    EXPECT_NEAR(std::log2(e1 / e2), integratorOrder(kind), 0.25) << "integrator " << int(kind);
  }
  EXPECT_LT(dragError(Integrator::Rk4, 0.01), 1e-8);
  EXPECT_LT(dragError(Integrator::VelocityVerlet, 0.01), 1e-3);
}

TEST(Integrator, QuadraticDragReachesTerminalVelocity) {
  // Falling from rest with F = -c|v|v: v(t) = vt tanh(g t / vt), vt = sqrt(m g / c).
  ForceModel f;
  f.quadratic_drag = 0.3;
  const double mass = 1.5, g = 9.81, vt = std::sqrt(mass * g / f.quadratic_drag);
  Particle p(Vec3::Zero(), Vec3::Zero());
  p.inv_mass = 1.0 / mass;
  for (int i = 0; i < 400; ++i) p.step(Integrator::Rk4, f, 0.005);
  EXPECT_NEAR(p.v.y(), -vt * std::tanh(g * 2.0 / vt), 1e-8);
}

/// Largest relative deviation of the oscillator's energy over a window of steps.
struct EnergyWindow {
  double early = 0.0, late = 0.0;
};

EnergyWindow oscillatorEnergy(Integrator kind, int steps, double dt) {
  const ForceModel f = oscillator(1.0);
  Particle p(Vec3(1, 0, 0), Vec3::Zero());
  EnergyWindow w;
  const int window = 10000;
  for (int i = 0; i < steps; ++i) {
    p.step(kind, f, dt);
    const double e = 0.5 * p.v.squaredNorm() + 0.5 * p.x.squaredNorm();
    const double dev = std::abs(e - 0.5) / 0.5;
    if (i < window) w.early = std::max(w.early, dev);
    if (i >= steps - window) w.late = std::max(w.late, dev);
  }
  return w;
}

TEST(Integrator, SymplecticEnergyStaysBoundedOverAMillionSteps) {
  const double dt = 0.01;
  for (Integrator kind :
       {Integrator::SemiImplicitEuler, Integrator::PositionVerlet, Integrator::VelocityVerlet}) {
    const EnergyWindow w = oscillatorEnergy(kind, 1000000, dt);
    std::printf("energy %d: first 1e4 steps %.3e, last 1e4 of 1e6 %.3e\n", int(kind), w.early,
                w.late);
    // Bounded, not drifting: the last window's excursion is the first window's to 1e-6.
    EXPECT_LT(w.late, w.early + 1e-6) << "integrator " << int(kind);
    // Semi-implicit Euler's shadow energy is off by O(dt), the Verlets' by O(dt^2).
    EXPECT_LT(w.late, kind == Integrator::SemiImplicitEuler ? 1.1 * dt : dt * dt);
  }
  // The contrast: explicit Euler gains energy every step, (1 + dt^2) per step.
  const EnergyWindow euler = oscillatorEnergy(Integrator::ExplicitEuler, 20000, dt);
  EXPECT_GT(euler.late, 1.0);
}

TEST(Integrator, TwoRunsAreBitwiseEqual) {
  ForceModel f = oscillator(3.0);
  f.linear_drag = 0.1;
  f.quadratic_drag = 0.05;
  for (Integrator kind : kAll) {
    Particle a(Vec3(1, 2, 3), Vec3(-1, 0.5, 2)), b(Vec3(1, 2, 3), Vec3(-1, 0.5, 2));
    for (int i = 0; i < 1000; ++i) {
      a.step(kind, f, 0.003);
      b.step(kind, f, 0.003);
    }
    EXPECT_EQ(std::memcmp(a.x.data(), b.x.data(), sizeof(double) * 3), 0);
    EXPECT_EQ(std::memcmp(a.v.data(), b.v.data(), sizeof(double) * 3), 0);
  }
}

}  // namespace
}  // namespace zonesim::physics
