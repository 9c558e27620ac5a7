// Work-precision figures: run time against error for each integrator and step size on the
// unit oscillator (to t = 10) and on a projectile with linear drag (to t = 3), and solver
// iterations (and substeps) against the drift of a 10-box stack after 10 s. CSV on stdout:
//   integrator,problem,kind,dt,seconds,error
//   solver,stack10,iterations,substeps,ms_per_step,drift_m
// plot_work_precision.py draws it (error log-log against time).

#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "physics/box_column.h"
#include "physics/integrator.h"
#include "physics/world.h"

namespace zp = zonesim::physics;
using zonesim::Vec3;

namespace {

const char* name(zp::Integrator k) {
  static const char* names[] = {"explicit_euler",  "semi_implicit_euler", "position_verlet",
                                "velocity_verlet", "rk2_midpoint",        "rk4"};
  return names[static_cast<int>(k)];
}

/// Integrates one particle to time t; returns the position error against `exact`.
double run(zp::Integrator kind, const zp::ForceModel& f, double inv_mass, Vec3 x, Vec3 v, double dt,
           double t, const Vec3& exact) {
  Vec3 x_out, v_out, prev = Vec3::Zero();
  zp::LinearIntegrator integrator;
  const int steps = static_cast<int>(std::lround(t / dt));
  for (int i = 0; i < steps; ++i) {
    zp::LinearStateView view{{&x, 1},     {&v, 1},    {&inv_mass, 1}, {&x_out, 1},
                             {&v_out, 1}, {&prev, 1}, i > 0,          {}};
    integrator.step(kind, f, view, dt);
    x = x_out;
    v = v_out;
  }
  return (x - exact).norm();
}

template <typename F>
double secondsPerRun(F&& f) {
  // Repeat until at least 20 ms have passed so that short runs are measurable.
  int reps = 0;
  const auto t0 = std::chrono::steady_clock::now();
  double elapsed = 0.0;
  do {
    f();
    ++reps;
    elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  } while (elapsed < 0.02);
  return elapsed / reps;
}

double stackDrift(int iterations, int substeps, double& ms_per_step,
                  zp::SolverKind kind = zp::SolverKind::GaussSeidel, int boxes = 10) {
  zp::WorldSettings settings;
  settings.solver.kind = kind;
  settings.solver.velocity_iterations = iterations;
  settings.substeps = substeps;
  zp::BoxColumn column(settings, std::vector<double>(std::size_t(boxes), 1000.0));
  const auto t0 = std::chrono::steady_clock::now();
  column.run(10.0);  // 600 steps
  ms_per_step =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() /
      600.0;
  return column.drift().total;
}

}  // namespace

int main() {
  zp::ForceModel oscillator;
  oscillator.gravity.setZero();
  oscillator.springs.push_back(zp::Spring{0, zp::kWorldAnchor, Vec3::Zero(), 1.0, 0.0, 0.0});
  zp::ForceModel drag;
  drag.linear_drag = 0.5;
  const double mass = 2.0, tau = mass / drag.linear_drag, t_drag = 3.0;
  const Vec3 v0(20, 15, 5), v_inf = drag.gravity * tau;
  const Vec3 drag_exact = v_inf * t_drag + tau * (v0 - v_inf) * (1.0 - std::exp(-t_drag / tau));
  const Vec3 osc_exact(std::cos(10.0), 0, 0);
  std::printf("integrator,problem,kind,dt,seconds,error\n");
  for (int k = 0; k < 6; ++k) {
    const auto kind = static_cast<zp::Integrator>(k);
    for (double dt : {0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001}) {
      double err = 0.0;
      const double s1 = secondsPerRun([&] {
        err = run(kind, oscillator, 1.0, Vec3(1, 0, 0), Vec3::Zero(), dt, 10.0, osc_exact);
      });
      std::printf("integrator,oscillator,%s,%g,%.4e,%.4e\n", name(kind), dt, s1, err);
      const double s2 = secondsPerRun(
          [&] { err = run(kind, drag, 1.0 / mass, Vec3::Zero(), v0, dt, t_drag, drag_exact); });
      std::printf("integrator,projectile_drag,%s,%g,%.4e,%.4e\n", name(kind), dt, s2, err);
    }
  }
  std::printf("solver,stack10,iterations,substeps,ms_per_step,drift_m\n");
  for (int substeps : {1, 4}) {
    for (int iterations : {2, 4, 8, 16, 32, 64}) {
      double ms = 0.0;
      const double drift = stackDrift(iterations, substeps, ms);
      std::printf("solver,stack10,%d,%d,%.4f,%.4e\n", iterations, substeps, ms, drift);
    }
  }
  // Every contact response on a 5-box column (one step of 1/60 s, 10 s): iterations against
  // the largest drift (the constraint error left), capped at 1 m (fallen).
  const std::pair<const char*, zp::SolverKind> kinds[] = {
      {"gauss_seidel", zp::SolverKind::GaussSeidel},
      {"sor_1.3", zp::SolverKind::Sor},
      {"jacobi", zp::SolverKind::Jacobi},
      {"soft_step", zp::SolverKind::SoftStep},
      {"projection", zp::SolverKind::Projection},
      {"conjugate_gradient", zp::SolverKind::ConjugateGradient},
      {"penalty", zp::SolverKind::Penalty}};
  std::printf("method,stack5,kind,iterations,ms_per_step,drift_m\n");
  for (const auto& [label, kind] : kinds) {
    for (int iterations : {1, 2, 4, 8, 16, 32}) {
      double ms = 0.0;
      const double drift = std::min(1.0, stackDrift(iterations, 1, ms, kind, 5));
      std::printf("method,stack5,%s,%d,%.4f,%.4e\n", label, iterations, ms, drift);
    }
  }
  return 0;
}
