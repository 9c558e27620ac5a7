#pragma once
// Road networks in a zone: each NPC population with `roads` travels a waypoint graph
// (ai::WaypointGraph: weighted, flagged, one-way edges), walking straight from node to node at
// its speed and, at each node, taking the first edge of a cheapest path to its goal over the
// edges it may use that are open then; at the goal it draws the next goal from its own random
// stream. An edge that closes (a timed closure) stops nobody already on it: decisions are
// made at nodes only, and an NPC with no open way waits at its node and asks again each tick.
// Its state is two integers that migrate with it (RoadTripData: the node it walks to and
// its goal); every rank holds the same graph and closures, so the same question
// gets the same answer anywhere and a zone run ends bitwise equal on any number of ranks.

#include <cstdint>
#include <memory>
#include <vector>

#include "zone_node/entity_store.h"
#include "zone_node/systems/step_context.h"

namespace zonesim {
struct NpcPopulation;
}  // namespace zonesim

namespace zonesim::zone {

/// Steps the road-network NPC populations of a scene.
class RoadMovement : public ZoneSystem {
 public:
  /// The road networks of `npcs` (the scene's NPC populations).
  explicit RoadMovement(const std::vector<NpcPopulation>& npcs);
  ~RoadMovement();

  /// Whether the scene has a road population at all.
  bool active() const override { return !networks_.empty(); }

  /// Moves the road NPCs through the tick (closures as at its start, tick * dt).
  void step(StepContext& ctx) override;

  /// The node after `from` on a cheapest path to `goal` for population `p` over the edges it
  /// may use that are open at `time`; -1 when there is none (and `goal` itself at the goal).
  int nextHop(std::size_t p, int from, int goal, double time);

 private:
  struct Network;
  Network* networkOf(std::int32_t population);

  std::vector<std::unique_ptr<Network>> networks_;
};

}  // namespace zonesim::zone
