#pragma once
// The arrays a crowd step reads and writes. The zone keeps its entities in dense arrays; it
// passes views of them here (no copies), plus the ghosts: agents owned by neighbouring ranks
// that are seen as neighbours but never written. Ids order every neighbour sum, so a step's
// result does not depend on how the arrays are ordered or on which rank owns which agent.

#include <cstdint>
#include <span>

#include "crowd/vec2.h"

namespace zonesim::crowd {

/// Agents a step updates: ids (unique, stable: the zone's EntityId values), positions and
/// velocities, all of the same length; pos and vel are overwritten with the new state.
struct AgentSpan {
  std::span<const std::uint64_t> ids;  ///< stable unique ids (order neighbour sums)
  std::span<Vec2> pos;                 ///< positions, updated in place
  std::span<Vec2> vel;                 ///< velocities, updated in place
  /// Number of agents.
  std::size_t size() const { return ids.size(); }
};

/// Read-only neighbours (ghosts of other ranks): seen by the step, never written.
struct GhostSpan {
  std::span<const std::uint64_t> ids;  ///< ids, disjoint from the owned agents' ids
  std::span<const Vec2> pos;           ///< positions
  std::span<const Vec2> vel;           ///< velocities
  /// Number of ghosts.
  std::size_t size() const { return ids.size(); }
};

}  // namespace zonesim::crowd
