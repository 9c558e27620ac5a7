// Rolling resistance against its analytic results. A solid sphere (I = 2/5 m R^2) rolling
// without slipping under a resisting torque c R N decelerates at a = (5/7) c g on the flat,
// so from v0 it stops after d = v0^2 / (2a) = 7 v0^2 / (10 c g). On an incline of angle theta
// it rests when tan(theta) <= c, and otherwise rolls down at a = (5/7) g (sin - c cos).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "physics/world.h"

namespace zonesim::physics {
namespace {

constexpr double kDt = 1.0 / 60.0;
constexpr double kRadius = 0.5;

WorldSettings withSolver(SolverKind kind) {
  WorldSettings settings;
  settings.solver.kind = kind;
  return settings;
}

/// A static slab tilted by `degrees` about z (its top face through the origin) and a sphere
/// resting on it at the origin, rolling downhill (+x along the slope) at v0.
struct Slope {
  World world;
  BodyIndex ball = 0;
  Vec3 down = Vec3::UnitX();  // Along the surface, downhill.

  Slope(SolverKind kind, double degrees, double c_rr, double v0) : world(withSolver(kind)) {
    const double theta = degrees * M_PI / 180.0;
    // Rotating by -theta about z tilts +x downwards.
    const Quat tilt(Eigen::AngleAxisd(-theta, Vec3::UnitZ()));
    const Vec3 normal = tilt * Vec3::UnitY();
    down = tilt * Vec3::UnitX();
    BodyDesc ground;
    ground.type = BodyType::Static;
    ground.shape = Shape::box(Vec3(200, 1, 20));
    ground.orientation = tilt;
    ground.position = -normal;  // Top face through the origin.
    world.addBody(ground);
    BodyDesc sphere;
    sphere.shape = Shape::sphere(kRadius);
    sphere.position = kRadius * normal;
    sphere.friction = 0.8;  // Enough to roll without slipping on these slopes.
    sphere.rolling_resistance = c_rr;
    sphere.linear_velocity = v0 * down;
    // Rolling without slipping: omega x (-R n) = -v, i.e. omega = (n x v) / R.
    sphere.angular_velocity = normal.cross(v0 * down) / kRadius;
    ball = world.addBody(sphere);
  }
  double travelled() const { return world.bodies().position[ball].dot(down); }
  double speed() const { return world.bodies().linear_velocity[ball].norm(); }
};

class RollingResistance : public ::testing::TestWithParam<SolverKind> {};

TEST_P(RollingResistance, StopsAtTheAnalyticDistanceOnTheFlat) {
  const double v0 = 3.0, c = 0.05, g = 9.81;
  Slope flat(GetParam(), 0.0, c, v0);
  const double expected = 7.0 * v0 * v0 / (10.0 * c * g);  // 12.84 m
  const double t_stop = v0 / (5.0 / 7.0 * c * g);          // 8.56 s
  for (int s = 0; s < static_cast<int>((t_stop + 2.0) / kDt); ++s) flat.world.step(kDt);
  std::printf(
      "rolling resistance %.2f from %.1f m/s: stopped after %.4f m (analytic %.4f m), "
      "speed %.2e m/s\n",
      c, v0, flat.travelled(), expected, flat.speed());
  EXPECT_NEAR(flat.travelled() / expected, 1.0, 0.01);
  EXPECT_LT(flat.speed(), 1e-3);
}

TEST_P(RollingResistance, WithoutItASphereRollsOn) {
  Slope flat(GetParam(), 0.0, 0.0, 3.0);
  for (int s = 0; s < 240; ++s) flat.world.step(kDt);
  EXPECT_NEAR(flat.travelled(), 12.0, 0.05);
  EXPECT_NEAR(flat.speed(), 3.0, 0.01);
}

TEST_P(RollingResistance, HoldsOnASlopeShallowerThanItsCoefficient) {
  // tan 5 deg = 0.087 < 0.12: the torque limit holds the sphere still.
  Slope slope(GetParam(), 5.0, 0.12, 0.0);
  for (int s = 0; s < 300; ++s) slope.world.step(kDt);
  std::printf("c 0.12 on 5 deg: moved %.2e m in 5 s\n", slope.travelled());
  EXPECT_LT(std::abs(slope.travelled()), 1e-3);
}

TEST_P(RollingResistance, RollsDownASteeperSlopeAtTheAnalyticAcceleration) {
  const double theta = 5.0 * M_PI / 180.0, c = 0.03, g = 9.81, t = 3.0;
  Slope slope(GetParam(), 5.0, c, 0.0);
  for (int s = 0; s < static_cast<int>(t / kDt); ++s) slope.world.step(kDt);
  const double a = 5.0 / 7.0 * g * (std::sin(theta) - c * std::cos(theta));
  std::printf("c 0.03 on 5 deg: %.4f m in %.0f s, analytic %.4f m\n", slope.travelled(), t,
              0.5 * a * t * t);
  EXPECT_NEAR(slope.travelled() / (0.5 * a * t * t), 1.0, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Solvers, RollingResistance,
                         ::testing::Values(SolverKind::GaussSeidel, SolverKind::SoftStep,
                                           SolverKind::Jacobi),
                         [](const auto& info) {
                           switch (info.param) {
                             case SolverKind::GaussSeidel:
                               return "GaussSeidel";
                             case SolverKind::SoftStep:
                               return "SoftStep";
                             default:
                               return "Jacobi";
                           }
                         });

TEST(RollingResistanceInput, NegativeOrNonFiniteOrUnsupportedIsRefusedByName) {
  World world;
  BodyDesc d;
  d.rolling_resistance = -0.1;
  try {
    world.addBody(d);
    FAIL() << "a negative coefficient was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rolling_resistance"), std::string::npos);
  }
  d.rolling_resistance = NAN;
  EXPECT_THROW(world.addBody(d), std::invalid_argument);
  EXPECT_EQ(world.bodies().size(), 0u);
  World projection(withSolver(SolverKind::Projection));
  d.rolling_resistance = 0.1;
  EXPECT_THROW(projection.addBody(d), std::invalid_argument);
}

}  // namespace
}  // namespace zonesim::physics
