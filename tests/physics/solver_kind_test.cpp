// The contact solvers selectable in SolverSettings::kind, each on the scene it is for, with
// the bounds measured at the default step (one step of 1/60 s, 10 velocity and 2
// position iterations) unless a test says otherwise.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "physics/box_column.h"
#include "physics/world.h"
#include "rebound.h"

namespace zonesim::physics {
namespace {

/// The shared stack scene, with the drift read as (horizontal, vertical) like the asserts.
struct Column : BoxColumn {
  Column(const WorldSettings& settings, const std::vector<double>& densities)
      : BoxColumn(settings, densities) {}
  void drift(double& horizontal, double& vertical) const {
    const Drift d = BoxColumn::drift();
    horizontal = d.horizontal;
    vertical = d.vertical;
  }
};

WorldSettings withSolver(SolverKind kind, int velocity_iterations = 10) {
  WorldSettings settings;
  settings.solver.kind = kind;
  settings.solver.velocity_iterations = velocity_iterations;
  settings.solver.position_iterations = 2;
  return settings;
}

// Plain PGS lets this column fall within 10 s at these settings (docs/physics.md). The soft
// step keeps it upright: no sideways walk, and the only drift is the contact springs' static
// sag, g / omega^2 per supported box (75 Hz here: 1.8 cm at the top of 20), which is over
// the 1 cm: the next test shows the iterations that meet it.
TEST(SoftStep, TwentyBoxStackStandsSixtySecondsAtOneStepAndTenIterations) {
  Column column(withSolver(SolverKind::SoftStep), std::vector<double>(20, 1000.0));
  column.run(60.0);
  double horizontal = 0.0, vertical = 0.0;
  column.drift(horizontal, vertical);
  std::printf("soft step, 20 boxes, 60 s: horizontal drift %.3e m, sag %.3e m\n", horizontal,
              vertical);
  EXPECT_LT(horizontal, 5e-3);  // Measured 0.14 mm.
  EXPECT_LT(vertical, 0.025);
}

// Seven sub-steps (14 velocity iterations) make the springs stiff enough (105 Hz) for the
// issue's bound: every box within 1 cm of where it started after 60 s.
TEST(SoftStep, TwentyBoxStackDriftsLessThanOneCentimetreWithFourteenIterations) {
  Column column(withSolver(SolverKind::SoftStep, 14), std::vector<double>(20, 1000.0));
  column.run(60.0);
  double horizontal = 0.0, vertical = 0.0;
  column.drift(horizontal, vertical);
  std::printf("soft step (14 it), 20 boxes, 60 s: horizontal drift %.3e m, sag %.3e m\n",
              horizontal, vertical);
  EXPECT_LT(std::hypot(horizontal, vertical), 0.01);
}

// A cube 100 times as dense on a light one, Gauss-Seidel at one step per 1/60 s for 30 s.
TEST(GaussSeidel, HundredToOneMassRatioStackHoldsAtOneStep) {
  Column column(withSolver(SolverKind::GaussSeidel), {1000.0, 100000.0});
  column.run(30.0);
  double horizontal = 0.0, vertical = 0.0;
  column.drift(horizontal, vertical);
  std::printf("PGS 100:1, 30 s: horizontal drift %.3e m, sag %.3e m\n", horizontal, vertical);
  EXPECT_LT(std::hypot(horizontal, vertical), 0.02);
}

// The same 100:1 pair under the soft step, whose relax passes (one per position iteration)
// settle the light box squeezed under the heavy one; with a single relax pass it rocked and
// walked 0.38 m in 30 s. A light-light-heavy column, which Gauss-Seidel drops, holds too; its
// sag is the contact springs' deflection under the heavy box (100 times the load).
TEST(SoftStep, HundredToOneMassRatioStacksHoldAtOneStep) {
  Column pair(withSolver(SolverKind::SoftStep), {1000.0, 100000.0});
  pair.run(30.0);
  double horizontal = 0.0, vertical = 0.0;
  pair.drift(horizontal, vertical);
  std::printf("soft step 100:1, 30 s: horizontal drift %.3e m, sag %.3e m\n", horizontal, vertical);
  EXPECT_LT(horizontal, 5e-3);  // Measured 0.87 mm.
  EXPECT_LT(vertical, 0.015);   // Measured 8.9 mm.
  Column column(withSolver(SolverKind::SoftStep), {1000.0, 1000.0, 100000.0});
  column.run(30.0);
  column.drift(horizontal, vertical);
  std::printf("soft step light-light-heavy, 30 s: horizontal drift %.3e m, sag %.3e m\n",
              horizontal, vertical);
  EXPECT_LT(horizontal, 5e-3);  // Measured 2.3 mm.
  EXPECT_LT(vertical, 0.025);   // Measured 1.8 cm.
}

// Restitution through the soft step: the bounce is applied once after the sub-steps.
TEST(SoftStep, RestitutionGivesTheExpectedReboundHeight) {
  const double h = 2.0, e = 0.6, r = 0.5, dt = 1.0 / 1000.0;
  const double apex = testing::reboundApex(withSolver(SolverKind::SoftStep), h, e, r, dt);
  std::printf("soft step rebound apex %.5f m, expected %.5f m\n", apex, e * e * h);
  EXPECT_NEAR(apex / (e * e * h), 1.0, 0.02);
}

struct KindBound {
  SolverKind kind;
  const char* name;
  double box_bound;    ///< Largest drift (m) of a resting cube after 10 s.
  double stack_bound;  ///< Largest drift (m) in a 3-cube column after 10 s.
};

// Every selectable response keeps a resting cube and a 3-cube column standing for 10 s at the
// issue's default step. The bounds are about twice what each measured (printed): the rigid
// iterative solvers hold to micrometres and millimetres, Jacobi sags more (its averaged updates
// converge slower), penalty springs sag by g / omega^2 per supported box (omega dt = 0.5) and
// projection drifts sideways (position-level friction has no memory between steps).
TEST(SolverKinds, EachKeepsARestingBoxAndASmallStackStanding) {
  const KindBound kinds[] = {
      {SolverKind::GaussSeidel, "gauss-seidel", 1e-5, 2e-3},
      {SolverKind::Sor, "sor 1.3", 1e-5, 2e-3},
      {SolverKind::Jacobi, "jacobi", 1e-3, 0.03},
      {SolverKind::SoftStep, "soft step", 1e-3, 5e-3},
      {SolverKind::Penalty, "penalty", 8e-3, 0.13},
      {SolverKind::Projection, "projection", 1e-3, 0.12},
      {SolverKind::ConjugateGradient, "conj. grad.", 1e-5, 2e-3},
  };
  for (const KindBound& k : kinds) {
    double h = 0.0, v = 0.0;
    Column box(withSolver(k.kind), {1000.0});
    box.run(10.0);
    box.drift(h, v);
    const double box_drift = std::hypot(h, v);
    Column stack(withSolver(k.kind), {1000.0, 1000.0, 1000.0});
    stack.run(10.0);
    stack.drift(h, v);
    const double stack_drift = std::hypot(h, v);
    std::printf("%-12s resting box drift %.3e m, 3-box column drift %.3e m\n", k.name, box_drift,
                stack_drift);
    EXPECT_LT(box_drift, k.box_bound) << k.name;
    EXPECT_LT(stack_drift, k.stack_bound) << k.name;
  }
}

// SOR with omega = 1 is Gauss-Seidel, bit for bit (the same code path, scaled by 1.0).
TEST(SolverKinds, SorWithOmegaOneIsGaussSeidel) {
  WorldSettings sor = withSolver(SolverKind::Sor);
  sor.solver.sor_omega = 1.0;
  Column a(sor, {1000.0, 1000.0, 1000.0});
  Column b(withSolver(SolverKind::GaussSeidel), {1000.0, 1000.0, 1000.0});
  a.run(2.0);
  b.run(2.0);
  for (std::size_t i = 0; i < a.world().bodies().size(); ++i) {
    EXPECT_EQ(a.world().bodies().position[i], b.world().bodies().position[i]);
  }
}

}  // namespace
}  // namespace zonesim::physics
