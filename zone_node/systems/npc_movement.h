#pragma once
// Walking NPCs: wander between random waypoints at their own top speed.

#include "common/scene.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

/// Steps every NPC of the store by dt; a reached waypoint is replaced by a new random one.
void stepNpcs(const Scene& scene, EntityStore& store, double dt);

}  // namespace zonesim::zone
