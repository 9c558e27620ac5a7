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
/// updates exact no-ops. prepare writes the anchors, separation, impulses and approach; buildRows
/// the masses. The passes compute the normal's angular Jacobians ra x n, rb x n and their images
/// under the inverse inertias from the anchors each time, with the operations buildRows uses:
/// the solve is bound by memory, and those 12 floats a point would more than double its bytes.
struct alignas(32) PointLanes {
  Lanes ra[3], rb[3];  // Anchors from the centres of mass.
  Lanes normal_mass;
  Lanes tangent_mass[2];
  Lanes separation;  // -depth at prepare; the soft passes move it with the bodies.
  Lanes normal_impulse, tangent_impulse[2];
  Lanes max_normal_impulse;  // Restitution applies only where the solve pushed (kept only then).
  Lanes approach;            // Relative normal velocity at prepare (restitution).
};

/// kBlockLanes constraints that share no movable body.
struct alignas(32) BlockLanes {
  std::uint32_t read_a[kBlockLanes], read_b[kBlockLanes];    // body slots read
  std::uint32_t write_a[kBlockLanes], write_b[kBlockLanes];  // the sink for immovable ones
  Lanes inv_mass_a, inv_mass_b;
  Lanes inv_inertia_a[6], inv_inertia_b[6];  // symmetric: xx yy zz xy xz yz
  Lanes normal[3], tangent[2][3];
  Lanes friction, restitution;
  Lanes fixed;        // 1 where one body is immovable: the static contact spring applies.
  Lanes point_count;  // the lane's points (0 for an empty lane)
  PointLanes point[kPoints];
  int points;  // Most points of any lane: the same for every width.
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
  bool track_pushes;  // keep max_normal_impulse (read only by restitution)
};

/// Builds each used point's effective masses along the normal and the tangents (zero at a lane's
/// unused points) from its anchors, the normal, tangents and the bodies' masses, in float,
/// `lanes` at a time.
void buildRows(int lanes, BlockLanes& block);
/// Applies the accumulated impulses (warm start), `lanes` at a time (1, 4 or 8).
void warmStart(int lanes, std::span<const BlockLanes> blocks, SolverBodies& bodies);
/// One soft pass (normals with the separation moved by the displacements, then friction).
void solve(int lanes, std::span<BlockLanes> blocks, SolverBodies& bodies, const SoftPass& pass);
/// Restitution once after the sub-steps, for points approaching faster than `threshold`.
void restitute(int lanes, std::span<BlockLanes> blocks, SolverBodies& bodies, float threshold);
/// The widest of 1, 4 and 8 lanes up to `wanted` that this CPU runs (8 needs AVX2).
int supportedLanes(int wanted);

}  // namespace zonesim::physics::wide
