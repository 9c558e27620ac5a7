#pragma once
// The bodies as the wide contact solver sees them during one step: float velocities and the
// displacement since the step began, in dense arrays indexed by body, plus two spare slots.
//
// Why a 32-byte record per body and not one array per component: a block's lanes gather
// bodies scattered over the world, and one record puts a body's whole velocity in one cache
// line (Box2D v3's b2BodyState). The constraints, which are read in order, are the ones laid out
// as structures of arrays (wide_contact_block.h).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace zonesim::physics {

/// Linear and angular velocity (or displacement and small rotation) of one body.
struct alignas(32) SolverMotion {
  float linear[3] = {0, 0, 0};
  float angular[3] = {0, 0, 0};
  float unused[2] = {0, 0};
};

/// Every body's solver state, plus a zero body that padding lanes read and a sink that lanes
/// of immovable bodies write to (so several lanes may share a static body).
struct SolverBodies {
  std::vector<SolverMotion> velocity;       ///< m/s and rad/s
  std::vector<SolverMotion> displacement;   ///< m and rad since the step began
  std::vector<SolverMotion> velocity_step;  ///< Force-driven velocity change per sub-step.

  /// Slot of the always-zero body.
  std::uint32_t zeroSlot() const { return static_cast<std::uint32_t>(velocity.size() - 2); }
  /// Slot written by lanes whose body does not move.
  std::uint32_t sinkSlot() const { return static_cast<std::uint32_t>(velocity.size() - 1); }
  /// Sizes the arrays for n bodies and the two spare slots, all zero.
  void reset(std::size_t n) {
    velocity.assign(n + 2, SolverMotion{});
    displacement.assign(n + 2, SolverMotion{});
    velocity_step.assign(n + 2, SolverMotion{});
  }
};

}  // namespace zonesim::physics
