// Cloth: static equilibrium against closed forms and conserved quantities, and tearing.

#include "physics/cloth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace zonesim::physics {
namespace {

TEST(Cloth, HangingChainSettlesToTheClosedFormStretch) {
  // One column of n particles pinned at the top: the spring above particle j carries the
  // weight of the n - j particles below it, so it is longer than rest by (n - j) m g / k.
  ClothDesc d;
  d.columns = 1;
  d.rows = 10;
  d.bend_stiffness = 0.0;
  d.spring_damping = 1.0;  // Settles in seconds; the equilibrium does not depend on it.
  Cloth cloth(d);
  cloth.pin(0);
  for (int s = 0; s < 60 * 30; ++s) cloth.step(1.0 / 60.0, 20);
  double worst = 0.0, y = 0.0;
  const double g = 9.81;
  for (int j = 1; j < d.rows; ++j) {
    y -= d.spacing + (d.rows - j) * d.particle_mass * g / d.stiffness;
    worst = std::max(worst, std::abs(cloth.positions()[j].y() - y));
  }
  std::printf("hanging chain: worst error against the closed form %.2e m (bottom at %.5f m)\n",
              worst, y);
  EXPECT_LT(worst, 1e-6);
}

TEST(Cloth, PatchPinnedAtTwoCornersHoldsItsWeightAtRest) {
  // At static equilibrium the pins must hold exactly the weight of the free particles.
  ClothDesc d;
  d.spring_damping = 0.5;
  Cloth cloth(d);
  cloth.pin(cloth.index(0, 0));
  cloth.pin(cloth.index(d.columns - 1, 0));
  for (int s = 0; s < 60 * 20; ++s) cloth.step(1.0 / 60.0, 20);
  const double weight = (d.columns * d.rows - 2) * d.particle_mass * 9.81;
  const Vec3 pins = cloth.pinForce();
  double lowest = 0.0;
  for (const Vec3& p : cloth.positions()) lowest = std::min(lowest, p.y());
  std::printf(
      "cloth at rest: kinetic energy %.2e J, pins hold %.6f N against weight %.6f N, "
      "lowest point %.4f m\n",
      cloth.kineticEnergy(), -pins.y(), weight, lowest);
  EXPECT_LT(cloth.kineticEnergy(), 1e-8);
  EXPECT_NEAR(-pins.y() / weight, 1.0, 1e-6);
  EXPECT_NEAR(pins.x(), 0.0, 1e-6 * weight);
  // Hanging from two corners it sags below its own height, and the middle of the top edge
  // dips below the pins: a catenary-like drape.
  EXPECT_LT(lowest, -(d.rows - 1) * d.spacing);
  EXPECT_LT(cloth.positions()[cloth.index(d.columns / 2, 0)].y(), -0.05);
}

TEST(Cloth, PullingTearsSpringsAndSplitsTheMesh) {
  // A strip pinned along its top row whose bottom row is pulled down: springs past 50 % strain
  // are removed until the strip is in pieces; none left is over the limit.
  ClothDesc d;
  d.columns = 4;
  d.rows = 8;
  d.tear_strain = 0.5;
  d.spring_damping = 0.5;
  Cloth cloth(d);
  for (int c = 0; c < d.columns; ++c) {
    cloth.pin(cloth.index(c, 0));
    cloth.pin(cloth.index(c, d.rows - 1));
  }
  const std::size_t springs = cloth.springs().size();
  EXPECT_EQ(cloth.pieceCount(), 1);
  int steps = 0;
  while (cloth.pieceCount() == 1 && steps < 600) {
    for (int c = 0; c < d.columns; ++c) cloth.positions()[cloth.index(c, d.rows - 1)].y() -= 0.005;
    cloth.step(1.0 / 60.0, 20);
    ++steps;
  }
  std::printf("tearing: %zu of %zu springs removed after %d steps, %d pieces\n", cloth.tornCount(),
              springs, steps, cloth.pieceCount());
  EXPECT_GE(cloth.pieceCount(), 2);
  EXPECT_GT(cloth.tornCount(), 0u);
  EXPECT_EQ(cloth.springs().size() + cloth.tornCount(), springs);
  for (const ClothSpring& s : cloth.springs()) {
    const double strain = (cloth.positions()[s.b] - cloth.positions()[s.a]).norm() / s.rest - 1;
    EXPECT_LE(strain, d.tear_strain);
  }
}

}  // namespace
}  // namespace zonesim::physics
