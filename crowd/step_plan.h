#pragma once
// Per-agent time steps for one tick, as chosen by the level of detail (lod.h): an agent with
// dt 0 is not updated this tick (it is still seen by its neighbours); one with a larger dt
// catches up the ticks it skipped. `steer` 0 asks for the cheap update (no neighbour query:
// follow the path or field only). Steps take an empty plan as "everyone, full detail".

#include <cstdint>
#include <span>

namespace zonesim::crowd {

/// Per-agent dt and detail for one step; both spans empty, or both as long as the agents.
struct StepPlan {
  std::span<const double> dt;           ///< seconds to advance each agent (0: skip it)
  std::span<const std::uint8_t> steer;  ///< 1: full steering with neighbours, 0: cheap update
  /// True when the plan says nothing (all agents at full detail with the step's dt).
  bool empty() const { return dt.empty(); }
};

}  // namespace zonesim::crowd
