#pragma once
// Walking NPCs: wander between random waypoints at their own top speed, keeping apart from
// other walkers (their own zone's and the neighbours' ghosts alike) when the scene asks for it.

#include "zone_node/entity_store.h"
#include "zone_node/systems/step_context.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::zone {

/// The wandering NPCs of a zone (those that neither flock, nor follow a crowd system, nor are
/// agents).
class WanderMovement : public ZoneSystem {
 public:
  explicit WanderMovement(const Scene& scene);
  bool active() const override { return active_; }
  /// Steps every wandering NPC by one tick; a reached waypoint is replaced by a new random one.
  /// Separation reads ctx.near (built over this tick's starting positions); all NPCs steer from
  /// those positions before any of them moves, so the result is the same on any decomposition.
  void step(StepContext& ctx) override;

 private:
  const Scene& scene_;
  bool active_ = false;
};

}  // namespace zonesim::zone
