#pragma once
// Walking NPCs: wander between random waypoints at their own top speed, keeping apart from
// other walkers (their own zone's and the neighbours' ghosts alike) when the scene asks for it.

#include "common/scene.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

class Neighbourhood;

/// Steps every NPC of the store by dt from simulated time `time`; a reached waypoint is
/// replaced by a new random one.
/// Separation reads `near` (built over this tick's starting positions); all NPCs steer from
/// those positions before any of them moves, so the result is the same on any decomposition.
void stepNpcs(const Scene& scene, EntityStore& store, const Neighbourhood& near, double time,
              double dt);

}  // namespace zonesim::zone
