// Explosions: the momentum a single body receives against closed forms.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "physics/world.h"

namespace zonesim::physics {
namespace {

TEST(Explosion, ImpulseFollowsTheFalloff) {
  // J(r) = J0 f(r) away from the centre, for each falloff, at r = 3 of R = 10.
  const Vec3 centre(1, 2, 3), offset = Vec3(1, 2, 2);  // |offset| = 3.
  const double j0 = 500.0, radius = 10.0, r = 3.0;
  const std::pair<Falloff, double> cases[] = {
      {Falloff::Constant, 1.0}, {Falloff::Linear, 0.7}, {Falloff::Quadratic, 0.49}};
  for (const auto& [falloff, factor] : cases) {
    World world;
    BodyDesc d;
    d.shape = Shape::sphere(0.5);
    d.position = centre + offset;
    const BodyIndex i = world.addBody(d);
    BodyDesc far = d;
    far.position = centre + Vec3(10.5, 0, 0);  // Outside the radius: untouched.
    const BodyIndex o = world.addBody(far);
    world.applyExplosionImpulse(centre, j0, radius, falloff);
    const Vec3 p = world.bodies().linear_velocity[i] / world.bodies().inv_mass[i];
    const Vec3 expected = j0 * factor * offset / r;
    EXPECT_LT((p - expected).norm(), 1e-12 * j0);
    EXPECT_EQ(world.bodies().linear_velocity[o], Vec3::Zero());
  }
}

/// Momentum after a linear-falloff blast of force F0 and radius R acting for tau on a body
/// starting at rest at r0, no gravity, with the given integrator.
double blastMomentum(Integrator integrator, double f0, double radius, double r0, double tau,
                     double dt, double& mass) {
  WorldSettings settings;
  settings.integrator = integrator;
  World world(settings);
  world.forces().gravity.setZero();
  BodyDesc d;
  d.shape = Shape::sphere(0.5);
  d.position = Vec3(r0, 0, 0);
  const BodyIndex i = world.addBody(d);
  mass = 1.0 / world.bodies().inv_mass[i];
  world.forces().blasts.push_back(Blast{Vec3::Zero(), f0, radius, Falloff::Linear, tau});
  const int steps = static_cast<int>(std::lround(tau / dt));
  for (int s = 0; s < steps + 10; ++s) world.step(dt);  // The blast ends after tau.
  EXPECT_TRUE(world.forces().blasts.empty());
  return world.bodies().linear_velocity[i].x() * mass;
}

TEST(Explosion, MomentumOfALastingBlastMatchesTheIntegral) {
  // Along the radius m r'' = F0 (1 - r/R): u = R - r obeys u'' = -w^2 u, w^2 = F0 / (m R), so
  // the momentum at tau is p = integral of F dt = m (R - r0) w sin(w tau) (while r < R).
  const double f0 = 2e5, radius = 10.0, r0 = 2.0, tau = 0.2;
  double mass = 0.0;
  const double rk4 = blastMomentum(Integrator::Rk4, f0, radius, r0, tau, 1.0 / 600.0, mass);
  const double w = std::sqrt(f0 / (mass * radius));
  const double exact = mass * (radius - r0) * w * std::sin(w * tau);
  const double euler =
      blastMomentum(Integrator::SemiImplicitEuler, f0, radius, r0, tau, 1.0 / 600.0, mass);
  std::printf("blast momentum: exact %.6f, RK4 %.6f (rel %.2e), semi-implicit %.6f (rel %.2e)\n",
              exact, rk4, std::abs(rk4 / exact - 1), euler, std::abs(euler / exact - 1));
  EXPECT_NEAR(rk4 / exact, 1.0, 1e-8);
  EXPECT_NEAR(euler / exact, 1.0, 1e-4);
}

}  // namespace
}  // namespace zonesim::physics
