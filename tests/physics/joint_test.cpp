#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "zone_node/physics/world.h"

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

}  // namespace
}  // namespace zonesim::physics
