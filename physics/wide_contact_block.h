#pragma once
// Internal to the wide contact solver (wide_contact_*.cpp): one block of kBlockLanes contact
// constraints as structures of arrays, one float per lane, and the passes over blocks.

#include <cstdint>
#include <span>

#include "physics/constraint_colouring.h"
#include "physics/solver_body_state.h"

namespace zonesim::physics::wide {

/// Contact points per constraint (a manifold's most).
constexpr int kPoints = 4;
using Lanes = float[kBlockLanes];

/// One contact point of every lane. Unused points (and lanes) are all zero, which makes their
/// updates exact no-ops. prepare writes the anchors, separation and impulses; buildRows the
/// masses. The solve is bound by memory, so a point holds only what the passes cannot compute
/// cheaply: they compute the normal's angular Jacobians ra x n, rb x n and their images under
/// the inverse inertias from the anchors each time, with the operations buildRows uses. Its
/// fields fill whole 64-byte lines in pairs, ordered so that the friction pass reads 6 of the 7
/// lines and the normal pass 5.
struct alignas(64) PointLanes {
  Lanes ra[3], rb[3];  // Anchors from the centres of mass.
  Lanes normal_impulse, normal_mass;
  Lanes separation;  // -depth at prepare; the soft passes move it with the bodies.
  Lanes unused;      // fills separation's line
  Lanes tangent_mass[2];
  Lanes tangent_impulse[2];
};
static_assert(sizeof(PointLanes) == 7 * 64);

/// kBlockLanes constraints that share no movable body.
struct alignas(64) BlockLanes {
  std::uint32_t read_a[kBlockLanes], read_b[kBlockLanes];    // body slots read
  std::uint32_t write_a[kBlockLanes], write_b[kBlockLanes];  // the sink for immovable ones
  Lanes inv_mass_a, inv_mass_b;
  Lanes inv_inertia_a[6], inv_inertia_b[6];  // symmetric: xx yy zz xy xz yz
  Lanes normal[3], tangent[2][3];
  Lanes friction, restitution;
  Lanes fixed;        // 1 where one body is immovable: the static contact spring applies.
  Lanes point_count;  // the lane's points (0 for an empty lane)
  int points;         // Most points of any lane: the same for every width.
  PointLanes point[kPoints];
};

/// What only restitution reads, for one block's points: kept beside the blocks, and only in a
/// world with a bouncy contact, so the passes of other worlds never stream it.
struct alignas(64) BounceLanes {
  Lanes approach[kPoints];            // Relative normal velocity at prepare.
  Lanes max_normal_impulse[kPoints];  // Restitution applies only where the solve pushed.
};

/// One sub-step's contact spring (Softness in float) for body-body and for fixed contacts.
struct SoftLanes {
  float bias_rate, mass_scale, impulse_scale;
};

/// What one soft pass needs besides the blocks and bodies.
struct SoftPass {
  SoftLanes soft, soft_fixed;
  bool use_bias;   // Soft spring pass; else the rigid relax pass.
  bool friction;   // Solve friction in this pass.
  float inv_h;     // 1 / sub-step
  float max_push;  // m/s
};

/// Builds each used point's effective masses along the normal and the tangents (zero at a lane's
/// unused points) from its anchors, the normal, tangents and the bodies' masses, in float,
/// `lanes` at a time.
void buildRows(int lanes, BlockLanes& block);
/// Applies the accumulated impulses (warm start), `lanes` at a time (1, 4 or 8).
void warmStart(int lanes, std::span<const BlockLanes> blocks, SolverBodies& bodies);
/// One soft pass (friction where the pass has it, then the normals with the separation moved
/// by the displacements). `bounces`, one per block or empty, keeps each point's largest normal
/// impulse for restitution.
void solve(int lanes, std::span<BlockLanes> blocks, std::span<BounceLanes> bounces,
           SolverBodies& bodies, const SoftPass& pass);
/// Restitution once after the sub-steps, for points approaching faster than `threshold`.
void restitute(int lanes, std::span<BlockLanes> blocks, std::span<const BounceLanes> bounces,
               SolverBodies& bodies, float threshold);
/// The widest of 1, 4 and 8 lanes up to `wanted` that this CPU runs (8 needs AVX2).
int supportedLanes(int wanted);

}  // namespace zonesim::physics::wide
