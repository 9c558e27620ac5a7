// The nonsmooth conjugate-gradient contact solver (SolverKind::ConjugateGradient) against
// projected Gauss-Seidel at equal iterations. A column of boxes resting in its exact contact
// configuration has the analytic answer "nothing moves": after one cold-started step (no warm
// start), whatever velocity the boxes keep is the solver's residual.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "physics/box_column.h"
#include "physics/world.h"

namespace zonesim::physics {
namespace {

WorldSettings coldStart(SolverKind kind, int iterations) {
  WorldSettings settings;
  settings.solver.kind = kind;
  settings.solver.velocity_iterations = iterations;
  settings.solver.position_iterations = 0;
  settings.solver.warm_starting = false;
  return settings;
}

/// Largest speed any box of a resting column of `boxes` keeps after one cold step.
double residualSpeed(SolverKind kind, int iterations, int boxes) {
  BoxColumn column(coldStart(kind, iterations), std::vector<double>(boxes, 1000.0));
  column.world().step(1.0 / 60.0);
  double fastest = 0.0;
  for (const Vec3& v : column.world().bodies().linear_velocity)
    fastest = std::max(fastest, v.norm());
  return fastest;
}

TEST(ConjugateGradient, LeavesLessResidualThanGaussSeidelAtEqualIterations) {
  for (int iterations : {10, 20, 40}) {
    const double gs = residualSpeed(SolverKind::GaussSeidel, iterations, 10);
    const double cg = residualSpeed(SolverKind::ConjugateGradient, iterations, 10);
    std::printf(
        "10-box column, one cold step, %d iterations: residual speed Gauss-Seidel %.3e "
        "m/s, conjugate gradient %.3e m/s (%.1fx less)\n",
        iterations, gs, cg, gs / cg);
    EXPECT_LT(cg, gs);
  }
}

TEST(ConjugateGradient, EndsEachStepWithProjectedImpulses) {
  // The last iteration is a plain sweep: no contact pulls, and friction stays in its cone.
  BoxColumn column(coldStart(SolverKind::ConjugateGradient, 10), std::vector<double>(10, 1000.0));
  for (int s = 0; s < 30; ++s) column.world().step(1.0 / 60.0);
  int contacts = 0;
  for (const BodyContact& c : column.world().contacts()) {
    for (int i = 0; i < c.manifold.count; ++i, ++contacts) {
      EXPECT_GE(c.impulse[i][0], 0.0);
      EXPECT_LE(std::abs(c.impulse[i][1]), c.friction * c.impulse[i][0] + 1e-12);
      EXPECT_LE(std::abs(c.impulse[i][2]), c.friction * c.impulse[i][0] + 1e-12);
    }
  }
  EXPECT_GT(contacts, 0);
}

}  // namespace
}  // namespace zonesim::physics
