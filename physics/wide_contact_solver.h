#pragma once
// The soft step solved wide (SolverKind::SoftStepWide): contact constraints graph-coloured
// into blocks of 8 that share no movable body, solved 4 (SSE2) or 8 (AVX2, chosen at run time)
// at once in float, on a float copy of the bodies' velocities. The algorithm is the soft step's
// (contact_solver_soft.cpp): sub-steps of a soft biased pass and a rigid relax pass, warm
// starting, friction and restitution; it differs in visiting order (colour by colour), in
// friction (both tangents clamped together to the Coulomb disc) and in precision (float).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "physics/body_storage.h"
#include "physics/constraint_colouring.h"
#include "physics/contact_solver.h"
#include "physics/solver_body_state.h"

namespace zonesim::physics {

namespace wide {
struct BlockLanes;
struct BounceLanes;
}

/// Contacts of one step as coloured blocks, and the passes of the wide soft step over them.
class WideContactSolver {
 public:
  WideContactSolver();
  ~WideContactSolver();
  WideContactSolver(const WideContactSolver&);
  WideContactSolver(WideContactSolver&&) noexcept;
  WideContactSolver& operator=(const WideContactSolver&);
  WideContactSolver& operator=(WideContactSolver&&) noexcept;

  /// Colours the contacts (or packs them in contact order: SolverSettings::wide_in_order) and
  /// builds their rows (anchors, effective masses, warm-start impulses, approach speeds) from
  /// the bodies' state, in float.
  void prepare(const BodyStorage& bodies, std::span<const BodyContact> contacts,
               const SolverSettings& settings);
  /// Applies the accumulated impulses to the solver bodies.
  void warmStart(SolverBodies& state);
  /// One soft pass: the spring with its bias (use_bias) or the rigid relax pass.
  void solve(SolverBodies& state, const Softness& soft, const Softness& soft_fixed, bool use_bias,
             double inv_h);
  /// Restitution, once after the sub-steps.
  void applyRestitution(SolverBodies& state);
  /// Writes the accumulated impulses back for next step's warm start.
  void storeImpulses(std::span<BodyContact> contacts) const;
  /// Lanes solved at once (1, 4 or 8), after what the CPU allows.
  int lanes() const { return lanes_; }
  /// The colouring (or in-order packing) of the last prepare.
  const ConstraintColouring& colouring() const { return colouring_; }

 private:
  // Each point's approach speed for restitution, in a world with a bouncy contact.
  void prepareBounces(const BodyStorage& bodies, std::span<const BodyContact> contacts);

  std::vector<wide::BlockLanes> blocks_;
  std::vector<wide::BounceLanes> bounces_;  // one per block, or none
  std::vector<ConstraintBodies> constraint_bodies_;
  ConstraintColouring colouring_;
  SolverSettings settings_;
  int lanes_ = 1;
  bool any_restitution_ = false;
};

}  // namespace zonesim::physics
