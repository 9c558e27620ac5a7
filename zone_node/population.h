#pragma once
// Initial entities of a scene. Every rank derives the same global list from the scene seed and
// keeps the entities whose start position it owns, so ids and initial states do not depend on
// the number of ranks (a precondition for decomposition invariance).

#include <cstdint>
#include <functional>

#include "zone_node/entity_store.h"

namespace zonesim {
struct Scene;
struct NpcPopulation;
}  // namespace zonesim

namespace zonesim::zone {

/// Creator "rank" of entities defined by the scene (ids identical for any rank count).
constexpr std::uint32_t kSceneCreator = 0xFFFF;

/// Calls keep(record) for every initial entity of the scene, in global id order. With a map,
/// NPCs start on open cells (throws SceneError when a region has none).
void forEachInitialEntity(const Scene& scene,
                          const std::function<void(const EntityRecordData&)>& keep);

/// Whether the population's NPCs wander (WanderMovement): those of a flock, flow crowd, ant
/// colony, road network or formation carry their population index and move with that system.
bool wanders(const NpcPopulation& p);

/// The id of scene.physics.bodies[k] (they follow every population's entities).
EntityId namedBodyId(const Scene& scene, std::size_t k);

/// Draws the next waypoint for an NPC around `from`, clamped to the world.
Vec3 nextWaypoint(const Scene& scene, const Vec3& from, double radius, std::uint64_t& rng_state,
                  EntityId id);

}  // namespace zonesim::zone
