#pragma once
// Scene keys for crowds and the world's obstacle map (docs/scene-format.md); internal to the
// scene loader, which calls one hook per key.

#include <string>

#include "common/scene_loader_node.h"
#include "common/scene_npcs.h"

namespace zonesim {

struct Scene;

/// Reads the optional top-level `map` key, doors included; relative map and field paths resolve
/// against the folder of the file that names them.
void readObstacleMap(const SceneMap& root, Scene& scene);

/// Reads the optional `goal` of a population's `flock` mapping (after its max_speed).
void readFlockGoal(const SceneMap& flock, const Scene& scene, NpcFlock& f);

/// Reads the optional top-level `lod` key.
void readCrowdLod(const SceneMap& root, Scene& scene);

/// Reads the optional `flow` block of an NPC population (after the map: a flow needs one).
void readNpcFlow(const SceneMap& population, const Scene& scene, NpcPopulation& p);

/// Reads the optional `formation` block of an NPC population (common/scene_loader_formation.cpp).
void readNpcFormation(const SceneMap& population, const Scene& scene, NpcPopulation& p);

/// Reads the optional `colony` block of an NPC population (common/scene_loader_colony.cpp).
void readNpcColony(const SceneMap& population, const Scene& scene, NpcPopulation& p);

/// Reads the optional `roads` block of an NPC population (common/scene_loader_roads.cpp).
void readNpcRoads(const SceneMap& population, const Scene& scene, NpcPopulation& p);

/// Reads `key`'s {radius, weight} section of `m` into the two values (defaults kept when
/// absent); a radius wider than the halo fails, since neighbours across a border are seen only
/// through it.
void readSeparation(const SceneMap& m, const Scene& scene, double& radius, double& weight);
/// `body_radius` of a flow or flock block: at least 0, and twice it less than the halo width
/// (a body sees the neighbours that could bind it within 2 (radius + reach)).
void readBodyRadius(const SceneMap& m, const Scene& scene, double& radius);

/// A point [x, y, z] on the ground plane inside the world (y is ignored).
ScenePoint readGroundPoint(const SceneNode& node, const Scene& scene);

}  // namespace zonesim
