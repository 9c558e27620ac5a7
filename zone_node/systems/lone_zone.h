#pragma once
// Steps zone systems as a lone zone's tick would, without the zone: for tests, benchmarks and
// tools that drive one system over a store of their own.

#include <cstdint>
#include <vector>

#include "crowd/vec2.h"
#include "zone_node/entity_store.h"
#include "zone_node/systems/neighbourhood.h"
#include "zone_node/systems/step_context.h"
#include "zone_node/tick_profile.h"

namespace zonesim::zone {

/// A lone zone's step context: no other ranks (no gather, sums are its own), no ghosts unless
/// given, `near` empty unless the caller builds it, and `players` for level of detail.
struct LoneZone {
  explicit LoneZone(double tick_dt) : dt(tick_dt) {}

  double dt;
  Neighbourhood near;
  std::vector<crowd::Vec2> players;
  Collectives cluster;
  TickCounters counters;  ///< of the last step

  /// The context of tick `tick` (counters cleared).
  StepContext at(EntityStore& store, std::uint64_t tick, const GhostStore* ghosts = nullptr) {
    counters = {};
    return {store, ghosts, near, dt, tick, double(tick) * dt, players, cluster, counters};
  }
  /// Steps `system` through tick `tick`; returns that tick's counters.
  const TickCounters& step(ZoneSystem& system, EntityStore& store, std::uint64_t tick,
                           const GhostStore* ghosts = nullptr) {
    StepContext ctx = at(store, tick, ghosts);
    system.step(ctx);
    return counters;
  }
};

}  // namespace zonesim::zone
