#pragma once
// What a zone system's step reads and writes. Every system has one step(StepContext&), so the
// zone's tick runs them alike, each timed into its own stage of the profile, and a system that
// needs the whole cluster (a gather, a sum) asks the context instead of talking MPI itself.

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "crowd/vec2.h"
#include "zone_node/entity_store.h"
#include "zone_node/ghost_store.h"
#include "zone_node/zone_layout.h"

namespace zonesim::zone {

class Neighbourhood;
struct TickCounters;

/// Every rank's values, concatenated in rank order (collective: every zone calls it in the
/// same tick). Empty on a lone zone, which then uses its own list.
using ClusterGather = std::function<std::vector<std::uint64_t>(const std::vector<std::uint64_t>&)>;
/// Replaces the values by their element-wise sum over all ranks (collective, exact in integers).
using ClusterSum = std::function<void(std::span<std::int64_t>)>;

/// Sends out[r] to each rank r and returns what each rank sent this one, by rank (collective: a
/// personalised all-to-all of bytes).
using ClusterSwap = std::function<std::vector<std::vector<std::uint8_t>>(
    const std::vector<std::vector<std::uint8_t>>&)>;

/// The cluster-wide calls a system may make during its step. The scene decides which systems
/// run, so every rank makes the same calls in the same order. Unset on a lone zone.
struct Collectives {
  ClusterGather gather;
  ClusterSum sum;
  ClusterSwap swap;
  int rank = 0;   ///< this zone's rank
  int ranks = 1;  ///< zones in the cluster
  /// This zone's ground-plane rectangle (the load balancer may move it): everywhere on a lone
  /// zone.
  ZoneRect zone{-kEverywhere, -kEverywhere, kEverywhere, kEverywhere};
  static constexpr double kEverywhere = 1e300;
};

/// One tick of one zone, as the systems see it.
struct StepContext {
  EntityStore& store;
  const GhostStore* ghosts;   ///< neighbours' entities within the halo (null: none)
  const Neighbourhood& near;  ///< walkers and their ghosts by cell, built at the tick's start
  double dt;                  ///< simulated seconds per tick
  std::uint64_t tick;         ///< the tick being stepped (0 first)
  double time;                ///< simulated seconds at its start: tick * dt
  /// Every player avatar of the cluster and the scene's observers (x, z), for level of detail;
  /// empty without `lod`.
  std::span<const crowd::Vec2> players;
  const Collectives& cluster;
  TickCounters& counters;  ///< the tick's figures: each system adds its own
};

/// A zone system: runs in one stage of the tick when the scene gives it something to do.
class ZoneSystem {
 public:
  virtual ~ZoneSystem() = default;
  /// Whether the scene has anything for this system (decided from the scene: all ranks agree).
  virtual bool active() const = 0;
  /// Advances what the system owns in `ctx.store` by one tick.
  virtual void step(StepContext& ctx) = 0;
  /// The per-entity values it reads on ghosts (the halo sends them; ghost_store.h).
  virtual std::vector<GhostColumn> ghostColumns() const { return {}; }
};

}  // namespace zonesim::zone
