#pragma once
// What a zone's navigation mesh keeps out, from the scene: the agent radius (map.agent_radius)
// and, with map.static_bodies, the footprints of the static scene bodies. Agents' planner and
// flow crowds build their meshes from the same settings, so both walk around the same walls.

#include <vector>

#include "ai/navmesh.h"
#include "crowd/map_frame.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::zone {

/// The footprints of the scene's static bodies on the map, in map units (cells): each body's
/// world bounds, so a turned box closes the cells of its bounding rectangle.
std::vector<ai::NavBox> staticFootprints(const Scene& scene, const crowd::MapFrame& frame);

/// The mesh's clearance in map units (map.agent_radius over the cell size).
ai::NavMeshConfig navMeshConfig(const Scene& scene, const crowd::MapFrame& frame);

/// The boxes the mesh closes: the static footprints with map.static_bodies, else none.
std::vector<ai::NavBox> navMeshBoxes(const Scene& scene, const crowd::MapFrame& frame);

}  // namespace zonesim::zone
