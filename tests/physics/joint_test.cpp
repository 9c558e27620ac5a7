#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "physics/world.h"

namespace zonesim::physics {
namespace {

TEST(DistanceJoint, PendulumPeriodMatchesTheory) {
  // A point mass on a 1 m rod from 10 degrees: T = 2 pi sqrt(L/g) (1 + a^2/16 + 11 a^4/3072).
  const double length = 1.0, g = 9.81, a0 = 10.0 * std::numbers::pi / 180.0, dt = 1.0 / 600.0;
  World world;
  BodyDesc bob;
  bob.type = BodyType::Particle;
  bob.shape = Shape::sphere(0.05);
  const Vec3 pivot(0, 2, 0);
  bob.position = pivot + length * Vec3(std::sin(a0), -std::cos(a0), 0);
  const BodyIndex i = world.addBody(bob);
  world.addDistanceJoint(DistanceJoint{i, kNoBody, Vec3::Zero(), pivot, length});
  // Times at which x crosses zero going the same way, interpolated within the step.
  std::vector<double> crossings;
  double worst_length_error = 0.0;
  double x_prev = world.bodies().position[i].x();
  for (int s = 1; s <= 6000; ++s) {
    world.step(dt);
    const Vec3& p = world.bodies().position[i];
    worst_length_error = std::max(worst_length_error, std::abs((p - pivot).norm() - length));
    if (x_prev > 0.0 && p.x() <= 0.0) crossings.push_back((s - 1 + x_prev / (x_prev - p.x())) * dt);
    x_prev = p.x();
  }
  ASSERT_GE(crossings.size(), 4u);
  const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  const double theory = 2.0 * std::numbers::pi * std::sqrt(length / g) *
                        (1.0 + a0 * a0 / 16.0 + 11.0 * std::pow(a0, 4) / 3072.0);
  std::printf("pendulum period %.5f s, theory %.5f s, worst length error %.2e m\n", period, theory,
              worst_length_error);
  EXPECT_NEAR(period / theory, 1.0, 2e-3);
  EXPECT_LT(worst_length_error, 1e-3);
}

TEST(DistanceJoint, HangingChainHoldsItsLinks) {
  // Five boxes joined corner to corner below a fixed point: every link keeps its length.
  World world;
  std::vector<BodyIndex> links;
  for (int k = 0; k < 5; ++k) {
    BodyDesc d;
    d.shape = Shape::box(Vec3(0.1, 0.2, 0.1));
    d.position = Vec3(0.3 * k, 10 - 0.5 * k, 0);  // Starts off the vertical: it swings.
    links.push_back(world.addBody(d));
  }
  world.addDistanceJoint(DistanceJoint{links[0], kNoBody, Vec3(0, 0.2, 0), Vec3(0, 10.3, 0), 0.1});
  for (int k = 1; k < 5; ++k) {
    world.addDistanceJoint(
        DistanceJoint{links[k - 1], links[k], Vec3(0, -0.2, 0), Vec3(0, 0.2, 0), 0.1});
  }
  for (int s = 0; s < 600; ++s) world.step(1.0 / 60.0);
  const auto& b = world.bodies();
  for (int k = 1; k < 5; ++k) {
    const Vec3 pa = b.position[links[k - 1]] + b.orientation[links[k - 1]] * Vec3(0, -0.2, 0);
    const Vec3 pb = b.position[links[k]] + b.orientation[links[k]] * Vec3(0, 0.2, 0);
    EXPECT_NEAR((pb - pa).norm(), 0.1, 0.01) << "link " << k;
  }
  // The chain hangs below its pivot rather than falling away.
  EXPECT_LT(b.position[links[4]].y(), 10.0);
  EXPECT_GT(b.position[links[4]].y(), 10.3 - 3.0);
}

/// Times at which x crosses zero going down, interpolated within the step; returns the mean
/// period over the recorded swings.
double meanPeriod(const std::vector<double>& crossings) {
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

/// Finite-amplitude factor of a pendulum's period: 1 + a^2/16 + 11 a^4/3072.
double amplitudeFactor(double a0) {
  return 1.0 + a0 * a0 / 16.0 + 11.0 * std::pow(a0, 4) / 3072.0;
}

TEST(BallJoint, PhysicalPendulumPeriodMatchesTheoryUnderEverySolverKind) {
  // A solid sphere (r = 0.1 m) hung 1 m below a world pivot by a ball joint, from 5 degrees:
  // T = 2 pi sqrt(I_pivot / (m g L)), I_pivot = 2/5 m r^2 + m L^2.
  const double r = 0.1, length = 1.0, g = 9.81, a0 = 5.0 * std::numbers::pi / 180.0;
  const double dt = 1.0 / 600.0;
  // Joints share each response's iterations (the soft step's sub-steps included).
  for (int kind = 0; kind <= static_cast<int>(SolverKind::Projection); ++kind) {
    WorldSettings settings;
    settings.solver.kind = static_cast<SolverKind>(kind);
    World world(settings);
    const Vec3 pivot(0, 3, 0);
    BodyDesc bob;
    bob.shape = Shape::sphere(r);
    bob.position = pivot + length * Vec3(std::sin(a0), -std::cos(a0), 0);
    bob.orientation = Quat(Eigen::AngleAxisd(a0, Vec3::UnitZ()));
    const BodyIndex i = world.addBody(bob);
    world.addBallJoint(BallJoint{i, kNoBody, Vec3(0, length, 0), pivot});
    std::vector<double> crossings;
    double worst_gap = 0.0, x_prev = world.bodies().position[i].x();
    for (int s = 1; s <= 6000; ++s) {
      world.step(dt);
      const auto& b = world.bodies();
      const Vec3 anchor = b.position[i] + b.orientation[i] * Vec3(0, length, 0);
      worst_gap = std::max(worst_gap, (anchor - pivot).norm());
      const double x = b.position[i].x();
      if (x_prev > 0.0 && x <= 0.0) crossings.push_back((s - 1 + x_prev / (x_prev - x)) * dt);
      x_prev = x;
    }
    ASSERT_GE(crossings.size(), 4u);
    const double theory = 2.0 * std::numbers::pi *
                          std::sqrt((0.4 * r * r + length * length) / (g * length)) *
                          amplitudeFactor(a0);
    const double period = meanPeriod(crossings);
    std::printf(
        "ball joint pendulum (solver %d) period %.5f s, theory %.5f s, worst anchor "
        "gap %.2e m\n",
        kind, period, theory, worst_gap);
    EXPECT_NEAR(period / theory, 1.0, 1e-4) << kind;
    EXPECT_LT(worst_gap, 1e-4) << kind;
  }
}

TEST(HingeJoint, PendulumPeriodAndAxisHoldUnderAnOffAxisTorque) {
  // A 0.2 x 1 x 0.2 m bar hinged at its top end about the world z axis, from 5 degrees, with
  // a steady torque about x trying to twist it off the axis. Theory about the hinge:
  // T = 2 pi sqrt(I_pivot / (m g d)), I_pivot = m (hx^2 + hy^2) / 3 + m hy^2, d = hy.
  const double hx = 0.1, hy = 0.5, g = 9.81, a0 = 5.0 * std::numbers::pi / 180.0;
  const double dt = 1.0 / 600.0;
  World world;
  const Vec3 pivot(0, 3, 0);
  BodyDesc bar;
  bar.shape = Shape::box(Vec3(hx, hy, hx));
  bar.orientation = Quat(Eigen::AngleAxisd(a0, Vec3::UnitZ()));
  bar.position = pivot + bar.orientation * Vec3(0, -hy, 0);
  const BodyIndex i = world.addBody(bar);
  world.addHingeJoint(HingeJoint{i, kNoBody, Vec3(0, hy, 0), pivot, Vec3::UnitZ(), Vec3::UnitZ()});
  const double m = 1.0 / world.bodies().inv_mass[i];
  std::vector<double> crossings;
  double worst_tilt = 0.0, worst_gap = 0.0, x_prev = world.bodies().position[i].x();
  for (int s = 1; s <= 6000; ++s) {
    world.applyTorque(i, Vec3(m * g * hy, 0, 0));  // As large as gravity's torque at 90 deg.
    world.step(dt);
    const auto& b = world.bodies();
    const Vec3 axis = b.orientation[i] * Vec3::UnitZ();
    worst_tilt = std::max(worst_tilt, std::asin(std::min(1.0, axis.cross(Vec3::UnitZ()).norm())));
    worst_gap =
        std::max(worst_gap, (b.position[i] + b.orientation[i] * Vec3(0, hy, 0) - pivot).norm());
    const double x = b.position[i].x();
    if (x_prev > 0.0 && x <= 0.0) crossings.push_back((s - 1 + x_prev / (x_prev - x)) * dt);
    x_prev = x;
  }
  ASSERT_GE(crossings.size(), 4u);
  const double inertia = m * (hx * hx + hy * hy) / 3.0 + m * hy * hy;
  const double theory =
      2.0 * std::numbers::pi * std::sqrt(inertia / (m * g * hy)) * amplitudeFactor(a0);
  const double period = meanPeriod(crossings);
  std::printf(
      "hinge pendulum period %.5f s, theory %.5f s, worst axis tilt %.2e rad, "
      "worst anchor gap %.2e m\n",
      period, theory, worst_tilt, worst_gap);
  EXPECT_NEAR(period / theory, 1.0, 2e-3);
  EXPECT_LT(worst_tilt, 1e-3);
  EXPECT_LT(worst_gap, 1e-3);
}

}  // namespace
}  // namespace zonesim::physics
