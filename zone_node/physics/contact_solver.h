#pragma once
// Sequential impulses (projected Gauss-Seidel) on contact constraints: normal with restitution
// and speculative gaps, two-tangent Coulomb friction bounded by the normal impulse, warm
// starting from the previous step's impulses, and split-impulse position correction.
//
// Why split impulses rather than Baumgarte: a Baumgarte bias is added to the real velocity, so
// pushing overlapping bodies apart injects kinetic energy (stacks jitter, resting bodies pop
// and restitution tests overshoot). Split impulses solve the positional error on separate
// pseudo-velocities that move positions this step and are then discarded: velocities, momenta
// and energy are left exactly as the velocity solve made them.

#include <cstdint>
#include <span>
#include <vector>

#include "zone_node/physics/body_storage.h"
#include "zone_node/physics/contact.h"

namespace zonesim::physics {

/// Iteration counts and tolerances of the contact solver.
struct SolverSettings {
  int velocity_iterations = 10;
  int position_iterations = 2;
  double split_beta = 0.2;             ///< Fraction of the overlap removed per step.
  double slop = 0.005;                 ///< Overlap (m) left alone so contacts persist.
  double restitution_threshold = 0.5;  ///< m/s: slower impacts do not bounce.
  bool warm_starting = true;
};

/// A manifold between two bodies, with the impulses solved for each point (for warm starts).
struct BodyContact {
  BodyIndex a = 0;
  BodyIndex b = 0;
  Manifold manifold;
  double friction = 0.0;
  double restitution = 0.0;
  /// Normal and two tangent impulses per point, from the last solve.
  std::array<std::array<double, 3>, 4> impulse{};
};

/// Solves one step's contacts in place on the bodies' velocities.
class ContactSolver {
 public:
  /// Builds the constraints (effective masses, restitution and speculative targets).
  void prepare(const BodyStorage& bodies, std::span<const BodyContact> contacts,
               const SolverSettings& settings, double dt);
  /// Applies last step's impulses, runs the velocity iterations, writes impulses back.
  void solveVelocities(BodyStorage& bodies, std::span<BodyContact> contacts);
  /// Runs the split-impulse iterations; the pseudo-velocities come back per body.
  void solvePositions(const BodyStorage& bodies);
  /// Pseudo linear velocity of body i from the last solvePositions.
  const Vec3& pseudoLinear(std::size_t i) const { return ps_v_[i]; }
  /// Pseudo angular velocity of body i from the last solvePositions.
  const Vec3& pseudoAngular(std::size_t i) const { return ps_w_[i]; }

 private:
  struct Point {
    Vec3 ra, rb;
    double normal_mass, tangent_mass[2];
    double target;  // Normal velocity the solve aims for (bounce or allowed approach).
    double depth;
    double jn, jt[2], jp;
  };
  struct Constraint {
    BodyIndex a, b;
    Vec3 n, t[2];
    double friction;
    int count;
    Point p[4];
  };

  std::vector<Constraint> constraints_;
  std::vector<Vec3> ps_v_, ps_w_;
  SolverSettings settings_;
  double dt_ = 0.0;
};

}  // namespace zonesim::physics
