// Implicit (backward) Euler for cloth springs against semi-implicit Euler. One particle on one
// spring of stiffness k (no damping) under semi-implicit Euler is stable exactly while
// h omega < 2, i.e. k < 4 m / h^2 (144 N/m for 10 g at 1/60 s); backward Euler is stable at
// any k and its fixed point is the exact static stretch m g / k.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "physics/cloth.h"

namespace zonesim::physics {
namespace {

constexpr double kDt = 1.0 / 60.0;
constexpr double kG = 9.81;

/// A particle of 10 g hanging from a pinned one on a single undamped spring.
Cloth pendulumSpring(double stiffness, ClothIntegrator integrator) {
  ClothDesc d;
  d.columns = 1;
  d.rows = 2;
  d.stiffness = stiffness;
  d.shear_stiffness = d.bend_stiffness = 0.0;
  d.spring_damping = 0.0;
  d.integrator = integrator;
  Cloth cloth(d);
  cloth.pin(0);
  return cloth;
}

/// Largest |y - rest place| the hanging particle reaches in `seconds` at one sub-step per step
/// (infinity once it is no longer finite).
double largestSwing(Cloth& cloth, double seconds) {
  double worst = 0.0;
  for (int s = 0; s < static_cast<int>(seconds / kDt); ++s) {
    cloth.step(kDt, 1);
    const double y = cloth.positions()[1].y();
    if (!std::isfinite(y)) return INFINITY;
    worst = std::max(worst, std::abs(y + cloth.desc().spacing));
  }
  return worst;
}

TEST(ClothImplicit, SemiImplicitEulerBlowsUpJustPastTheAnalyticStiffnessImplicitDoesNot) {
  const double k_crit = 4.0 * 0.01 / (kDt * kDt);  // 144 N/m
  for (double k : {0.97 * k_crit, 1.03 * k_crit}) {
    Cloth semi = pendulumSpring(k, ClothIntegrator::SemiImplicitEuler);
    Cloth implicit = pendulumSpring(k, ClothIntegrator::ImplicitEuler);
    const double semi_swing = largestSwing(semi, 10.0);
    const double implicit_swing = largestSwing(implicit, 10.0);
    std::printf(
        "k = %.1f N/m (%.2f of 4 m / h^2): largest swing semi-implicit %.3e m, implicit "
        "%.3e m\n",
        k, k / k_crit, semi_swing, implicit_swing);
    // The swing about the static place starts at m g / k (the particle starts at rest length).
    const double sag = 0.01 * kG / k;
    if (k < k_crit) {
      EXPECT_LT(semi_swing, 100.0 * sag);  // Bounded (semi-implicit Euler's modified energy).
    } else {
      EXPECT_GT(semi_swing, 1e6 * sag);  // |lambda| = 1.10 per step: out of bounds in 10 s.
    }
    EXPECT_LE(implicit_swing, 2.0 * sag + 1e-12);
  }
}

TEST(ClothImplicit, BackwardEulerSettlesAStiffSpringAtTheExactStaticStretch) {
  for (double k : {1e3, 1e6, 1e9}) {
    Cloth cloth = pendulumSpring(k, ClothIntegrator::ImplicitEuler);
    largestSwing(cloth, 2.0);
    const double stretch = -cloth.positions()[1].y() - cloth.desc().spacing;
    const double expected = 0.01 * kG / k;
    std::printf("k = %.0e N/m: stretch %.6e m, m g / k %.6e m, %d CG iterations, residual %.1e\n",
                k, stretch, expected, cloth.implicitIterations(), cloth.implicitResidual());
    EXPECT_NEAR(stretch / expected, 1.0, 1e-6);
    EXPECT_LT(std::abs(cloth.velocities()[1].y()), 1e-9);
  }
}

/// A 10 x 10 patch pinned at its top corners, one sub-step per 1/60 s for 5 s: does it stay
/// finite and slower than 100 m/s?
bool patchHolds(double stiffness, ClothIntegrator integrator) {
  ClothDesc d;
  d.stiffness = stiffness;
  d.shear_stiffness = stiffness / 4.0;
  d.bend_stiffness = stiffness / 20.0;
  d.integrator = integrator;
  Cloth cloth(d);
  cloth.pin(cloth.index(0, 0));
  cloth.pin(cloth.index(d.columns - 1, 0));
  for (int s = 0; s < 300; ++s) {
    cloth.step(kDt, 1);
    for (const Vec3& v : cloth.velocities()) {
      if (!v.allFinite() || v.norm() > 100.0) return false;
    }
  }
  return true;
}

TEST(ClothImplicit, APatchHoldsAtEveryStiffnessWhereSemiImplicitEulerBlowsUp) {
  double semi_limit = 0.0;
  for (double k = 10.0; k <= 1.3e6; k *= 2.0) {
    const bool semi = patchHolds(k, ClothIntegrator::SemiImplicitEuler);
    if (!semi && semi_limit == 0.0) semi_limit = k;
    EXPECT_TRUE(patchHolds(k, ClothIntegrator::ImplicitEuler)) << "implicit at k = " << k;
  }
  std::printf(
      "10 x 10 patch, one sub-step of 1/60 s: semi-implicit Euler blows up from k = %.0f "
      "N/m; implicit Euler holds up to 1.3e6 N/m\n",
      semi_limit);
  EXPECT_GT(semi_limit, 0.0);    // Semi-implicit does blow up within the sweep...
  EXPECT_LT(semi_limit, 200.0);  // ...below the default stiffness, hence the zone's sub-steps.
}

TEST(ClothImplicit, OneImplicitSubStepDrapesLikeManySemiImplicitOnes) {
  // The same patch at rest after 20 s: the static drape is the fixed point of both.
  auto drape = [](ClothIntegrator integrator, int substeps) {
    ClothDesc d;
    d.spring_damping = 0.5;
    d.integrator = integrator;
    Cloth cloth(d);
    cloth.pin(cloth.index(0, 0));
    cloth.pin(cloth.index(d.columns - 1, 0));
    for (int s = 0; s < 1200; ++s) cloth.step(kDt, substeps);
    return cloth;
  };
  const Cloth reference = drape(ClothIntegrator::SemiImplicitEuler, 32);
  const Cloth implicit = drape(ClothIntegrator::ImplicitEuler, 1);
  double worst = 0.0;
  for (std::size_t i = 0; i < reference.positions().size(); ++i) {
    worst = std::max(worst, (reference.positions()[i] - implicit.positions()[i]).norm());
  }
  std::printf(
      "drape after 20 s: implicit (1 sub-step) against semi-implicit (32): largest "
      "distance %.2e m; kinetic energy %.1e and %.1e J\n",
      worst, implicit.kineticEnergy(), reference.kineticEnergy());
  EXPECT_LT(worst, 1e-4);
}

}  // namespace
}  // namespace zonesim::physics
