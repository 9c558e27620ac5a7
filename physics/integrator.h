#pragma once
// Integrators for force-driven translational motion, selectable per scene. They advance whole
// arrays with one switch per step (not per body) and reuse scratch buffers, so a warmed-up step
// allocates nothing.

#include <cstdint>
#include <span>
#include <vector>

#include "common/math.h"
#include "physics/forces.h"

namespace zonesim::physics {

/// The available integration schemes; global orders 1, 1, 2, 2, 2, 4 in that order.
enum class Integrator : std::uint8_t {
  ExplicitEuler,
  SemiImplicitEuler,
  PositionVerlet,
  VelocityVerlet,
  Rk2Midpoint,
  Rk4
};

/// The theoretical global order of convergence of an integrator.
int integratorOrder(Integrator kind);

/// Views of the translational state of n bodies; x_out and v_out receive the new state.
struct LinearStateView {
  std::span<const Vec3> x;
  std::span<const Vec3> v;
  std::span<const double> inv_mass;
  std::span<Vec3> x_out;
  std::span<Vec3> v_out;
  /// Position Verlet's previous positions; rebuilt from (x, v) when history_valid is false.
  std::span<Vec3> x_prev;
  bool history_valid = false;
  /// Per-body applied forces held constant over the step; empty for none.
  std::span<const Vec3> external_force;
};

/// Advances force-driven motion by one step with the chosen scheme.
class LinearIntegrator {
 public:
  /// One step of length dt; x_out/v_out must not alias x/v (they are read to the end).
  void step(Integrator kind, const ForceModel& forces, const LinearStateView& state, double dt);

 private:
  void resize(std::size_t n);
  void explicitEuler(const ForceModel& f, const LinearStateView& s, double dt);
  void semiImplicitEuler(const ForceModel& f, const LinearStateView& s, double dt);
  void positionVerlet(const ForceModel& f, const LinearStateView& s, double dt);
  void velocityVerlet(const ForceModel& f, const LinearStateView& s, double dt);
  void rk2Midpoint(const ForceModel& f, const LinearStateView& s, double dt);
  void rk4(const ForceModel& f, const LinearStateView& s, double dt);

  // Stage buffers: accelerations and the intermediate states the multi-stage schemes need.
  std::vector<Vec3> a1_, a2_, a3_, a4_;
  std::vector<Vec3> xs_, vs_, v2_, v3_, v4_;
};

}  // namespace zonesim::physics
