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

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "physics/body_storage.h"
#include "physics/contact.h"
#include "physics/contact_recycling.h"
#include "physics/softness.h"
#include "physics/union_find.h"

namespace zonesim::physics {

/// How contacts are resolved (WorldSettings::solver.kind). See docs/physics.md.
enum class SolverKind {
  /// Box2D v3 soft step: the velocity iterations become sub-steps of the solve (TGS), each a
  /// soft (spring-damper) biased pass and a rigid relax pass, with separations updated from
  /// the bodies' motion inside the step. Holds tall stacks and mass ratios at one world step.
  SoftStep,
  /// Projected Gauss-Seidel sequential impulses with split-impulse position correction.
  GaussSeidel,
  /// Gauss-Seidel with successive over-relaxation: each impulse update is scaled by sor_omega.
  Sor,
  /// Projected Jacobi: every row is updated from the same velocities, then all are applied,
  /// each scaled by 1 / (rows on the busier body) so that neighbours do not overshoot.
  Jacobi,
  /// Penalty: explicit spring-damper forces on the overlap, no iterations (soft by nature).
  Penalty,
  /// Projection (position based): overlaps are removed from the step's displacements by
  /// velocity_iterations Gauss-Seidel position passes, and velocities are the displacement / dt.
  Projection,
  /// Nonsmooth nonlinear conjugate gradients (Silcowitz, Niebe and Erleben): each Gauss-Seidel
  /// sweep is a step along the gradient of the contact problem, and the impulses then move on
  /// along the previous search direction by the Fletcher-Reeves ratio, restarting whenever the
  /// ratio exceeds 1. Same cost per iteration as Gauss-Seidel, faster convergence on stacks.
  ConjugateGradient,
  /// The soft step solved wide (wide_contact_solver.h): the same sub-steps, with contacts
  /// graph-coloured into blocks solved 4 or 8 at once in float. Bitwise the same at every width.
  /// Rolling resistance is not solved by it.
  SoftStepWide,
};

/// Iteration counts and tolerances of the contact solver.
struct SolverSettings {
  SolverKind kind = SolverKind::GaussSeidel;
  int velocity_iterations = 10;
  int position_iterations = 2;
  double split_beta = 0.2;  ///< Fraction of the overlap removed per step.
  double slop = 0.005;      ///< Overlap (m) left alone so contacts persist.
  /// m/s: slower impacts do not bounce (the world raises it to 2.5 g dt for resting contact).
  double restitution_threshold = 0.5;
  bool warm_starting = true;
  double sor_omega = 1.3;  ///< SOR: over-relaxation factor (1 is plain Gauss-Seidel).
  /// Penalty: spring frequency as a fraction of the step rate; omega dt = 2 pi * 0.08 = 0.5
  /// keeps the explicit spring and its damper stable.
  double penalty_rate_fraction = 0.08;
  double penalty_damping_ratio = 0.7;  ///< Penalty: damping ratio of the contact spring.
  /// Soft step: contact spring frequency, capped at contact_rate_fraction of the sub-step
  /// rate (the default asks for the cap: 75 Hz at 1/60 s and 10 iterations).
  double contact_hertz = 1000.0;
  /// Soft step: the cap on body-body contact springs as a fraction of the sub-step rate.
  /// Stiffer means less sag but a narrower stable margin (docs/physics.md, soft_step_sweep).
  double contact_rate_fraction = 0.25;
  /// Soft step: the same cap for contacts with a static or kinematic body.
  double static_contact_rate_fraction = 0.25;
  /// Soft step: contact spring damping ratio (heavily overdamped: no bounce from the spring).
  double contact_damping_ratio = 10.0;
  /// Soft step: joint spring frequency (Box2D's default), capped at a quarter of the sub-step
  /// rate. Joints stretch under load by about weight / (effective mass (2 pi hertz)^2).
  double joint_hertz = 60.0;
  /// Soft step: joint spring damping ratio.
  double joint_damping_ratio = 2.0;
  /// Soft step: the fastest the spring may push overlapping bodies apart (m/s).
  double max_push_velocity = 3.0;
  /// Wide soft step: the most constraints solved at once, 1 (scalar reference), 4 (SSE2) or 8
  /// (AVX2 where the CPU has it, else 4). The result is the same at every width.
  int wide_lanes = 8;
  /// Wide soft step: friction in the biased pass of each sub-step as well as in the relax
  /// passes. Off, as Box2D v3.2: friction is solved in the relax passes only, which leaves the
  /// biased pass half the work.
  bool friction_in_biased_pass = false;
  /// Wide soft step: pack the contacts into blocks in their own order
  /// (ConstraintColouring::buildInOrder), which solves them exactly as one by one in contact
  /// order, instead of graph-colouring them (ConstraintColouring::build). Neither order is the
  /// steadier everywhere (docs/benchmarks.md): contact order holds Box3D's many_pyramids (the
  /// colour order lets their boxes drift out of the pyramids' plane) but not Jolt's pyramid.
  bool wide_in_order = false;
};

/// A manifold between two bodies, with the impulses solved for each point (for warm starts).
struct BodyContact {
  BodyIndex a = 0;
  BodyIndex b = 0;
  /// The pieces of a and b that touch: a compound's part index, 0 for any other shape. A pair
  /// of bodies has one contact per touching pair of pieces.
  std::uint16_t piece_a = 0;
  std::uint16_t piece_b = 0;
  Manifold manifold;
  double friction = 0.0;
  double restitution = 0.0;
  /// Normal and two tangent impulses per point, from the last solve.
  std::array<std::array<double, 3>, 4> impulse{};
  /// Rolling resistance: the largest resisting angular impulse per unit normal impulse (c_rr
  /// of the pair times the rolling radius, m); 0 when neither body rolls.
  double rolling = 0.0;
  /// Angular impulses against rolling about the contact's two tangents, from the last solve.
  std::array<double, 2> rolling_impulse{};
  /// Where the manifold was computed: an index into the origins kept with the contact list
  /// (World's, or WarmStarts::origins), or kNoOrigin. Out of line because an origin is 256
  /// bytes, which every copy, sort and merge of the contacts and prepare's scattered reads
  /// would carry even with recycling off (the contact is 352 bytes without it, 640 with).
  std::uint32_t origin = kNoOrigin;
  /// True when this step carried the manifold along instead of computing it (its impulses are
  /// then already last step's).
  bool recycled = false;

  /// The order of a step's contacts: by body pair, then piece pair.
  friend bool operator<(const BodyContact& x, const BodyContact& y) {
    if (x.a != y.a) return x.a < y.a;
    if (x.b != y.b) return x.b < y.b;
    if (x.piece_a != y.piece_a) return x.piece_a < y.piece_a;
    return x.piece_b < y.piece_b;
  }
};

/// True when both contacts are between the same pieces of the same bodies.
inline bool samePieces(const BodyContact& x, const BodyContact& y) {
  return x.a == y.a && x.b == y.b && x.piece_a == y.piece_a && x.piece_b == y.piece_b;
}

/// Solves one step's contacts in place on the bodies' velocities.
class ContactSolver {
 public:
  /// Builds the constraints (effective masses, restitution and speculative targets).
  void prepare(const BodyStorage& bodies, std::span<const BodyContact> contacts,
               const SolverSettings& settings, double dt);
  /// Applies last step's impulses.
  void warmStart(BodyStorage& bodies);
  /// One velocity iteration over all contacts (normals, then friction); omega scales each
  /// impulse update (successive over-relaxation; 1 is Gauss-Seidel).
  void iterate(BodyStorage& bodies, double omega = 1.0);
  /// One projected Jacobi iteration (all rows from the same velocities, averaged per body).
  void iterateJacobi(BodyStorage& bodies);
  /// One nonsmooth conjugate-gradient iteration (contact_solver_cg.cpp): a Gauss-Seidel sweep,
  /// then, unless `last`, the momentum step along the search direction. `first` starts a new
  /// direction (the first iteration of a step). Each group of contacts linked through movable
  /// bodies takes its own step length and restarts on its own, so an island converges as it
  /// would alone, bit for bit, whatever else the world holds.
  void iterateConjugateGradient(BodyStorage& bodies, bool first, bool last);
  /// |lambda after - lambda before| of the last conjugate-gradient sweep, in N s: how far the
  /// impulses still moved (zero at convergence).
  double lastSweepChange() const { return cg_change_; }
  /// Penalty response: one explicit spring-damper impulse per point over dt, and Coulomb
  /// friction capped by it.
  void applyPenalty(BodyStorage& bodies);
  /// Projection: one Gauss-Seidel pass removing overlap (and, up to the Coulomb bound, sliding
  /// at the contact) from the displacements dp and small rotations dtheta of this step.
  void projectPositions(std::span<Vec3> dp, std::span<Vec3> dtheta);
  /// One Gauss-Seidel pass over the rolling resistance rows (every solver but Projection runs
  /// it after its friction pass).
  void solveRolling(BodyStorage& bodies);
  /// Writes the accumulated impulses back for next step's warm start.
  void storeImpulses(std::span<BodyContact> contacts) const;
  /// The settings given to the last prepare.
  const SolverSettings& settings() const { return settings_; }
  /// Runs the split-impulse iterations; the pseudo-velocities come back per body.
  void solvePositions(const BodyStorage& bodies);
  /// Zero pseudo-velocities for n bodies (responses without split impulses).
  void clearPositionCorrection(std::size_t n) {
    ps_v_.assign(n, Vec3::Zero());
    ps_w_.assign(n, Vec3::Zero());
  }
  /// Pseudo linear velocity of body i from the last solvePositions.
  const Vec3& pseudoLinear(std::size_t i) const { return ps_v_[i]; }
  /// Soft step: one pass over every contact with the separations moved by each body's
  /// displacement dp and small rotation dtheta since prepare. use_bias: soft spring pass
  /// (pushes overlap out), else rigid relax pass (removes the push velocity).
  /// soft_static is the spring of contacts with a body of zero inverse mass.
  void solveSoft(BodyStorage& bodies, std::span<const Vec3> dp, std::span<const Vec3> dtheta,
                 const Softness& soft, const Softness& soft_static, bool use_bias, double inv_h);
  /// Soft step: applies the restitution targets once after the sub-steps.
  void applyRestitution(BodyStorage& bodies);
  /// Pseudo angular velocity of body i from the last solvePositions.
  const Vec3& pseudoAngular(std::size_t i) const { return ps_w_[i]; }

 private:
  // One Jacobian row along a direction d: the angular parts r x d and their images under the
  // world inverse inertia are computed once per step, so an iteration applies an impulse with
  // additions only (no 3x3 products in the inner loop).
  struct Row {
    Vec3 ca, cb;  // ra x d, rb x d.
    Vec3 wa, wb;  // I_a^-1 (ra x d), I_b^-1 (rb x d).
    double mass;  // 1 / (effective inverse mass along d).
  };
  // Normal and friction data of the points live in separate flat arrays: each pass of an
  // iteration streams only the rows it solves, which halves memory traffic on big scenes.
  struct NormalPoint {
    Row row;
    double target;  // Normal velocity the solve aims for (bounce or allowed approach).
    double depth;
    double jp;      // Split impulse (the normal impulse lives in jn_).
    double vn0;     // Relative normal velocity at prepare (restitution in the soft step).
    double max_jn;  // Largest normal impulse of the soft step (restitution only if touched).
  };
  struct FrictionPoint {
    Row row[2];  // The impulses live in jt_.
  };
  // Rolling resistance of one contact: angular rows about its two tangents, limited together
  // (a disc) by rolling times the contact's total normal impulse.
  struct RollingRow {
    std::uint32_t constraint;
    double rolling;
    Vec3 wa[2], wb[2];  // I_a^-1 t, I_b^-1 t.
    double mass[2];     // 1 / (t . (I_a^-1 + I_b^-1) t).
    std::array<double, 2> impulse;
  };
  struct Constraint {
    BodyIndex a, b;
    double ma, mb;  // Inverse masses.
    Vec3 n, t[2];
    double friction;
    double restitution;
    std::uint32_t first;  // Index of the first point in the point arrays.
    int count;
  };

  std::vector<Constraint> constraints_;
  std::vector<NormalPoint> normal_;
  std::vector<FrictionPoint> friction_;
  std::vector<RollingRow> rolling_;
  // Accumulated normal and friction impulses per point, apart from the rows: the friction pass
  // reads them for every point but the rows only of points that carry load, and a loaded
  // pyramid's side points (most of them) then cost 24 bytes instead of two cache lines.
  std::vector<double> jn_;
  std::vector<std::array<double, 2>> jt_;
  std::vector<Vec3> ps_v_, ps_w_;
  std::vector<Vec3> jac_v_, jac_w_;       // Jacobi: velocities the iteration reads.
  // Conjugate gradients: impulses before the sweep and the search direction, three per point
  // (normal, two tangents); per contact group (cg_group_ per constraint) the squared gradient
  // of this sweep and of the previous one, and the momentum factor.
  std::vector<double> cg_before_, cg_direction_;
  std::vector<std::uint32_t> cg_group_;
  std::vector<std::uint32_t> cg_group_of_root_;  // per body: its group while grouping
  UnionFind cg_sets_;
  std::vector<double> cg_g2_, cg_previous_, cg_beta_;
  double cg_change_ = 0.0;
  std::vector<std::uint16_t> row_count_;  // Jacobi: contact points touching each body.
  SolverSettings settings_;
  double dt_ = 0.0;
};

}  // namespace zonesim::physics
