#include "zone_node/systems/navmesh_obstacles.h"

#include "common/scene.h"
#include "physics/aabb.h"
#include "zone_node/systems/scene_shapes.h"

namespace zonesim::zone {

std::vector<ai::NavBox> staticFootprints(const Scene& scene, const crowd::MapFrame& frame) {
  std::vector<ai::NavBox> boxes;
  for (const SceneBody& b : scene.physics.bodies) {
    if (b.motion != SceneBody::Motion::Static) continue;
    const physics::Aabb a =
        physics::shapeBounds(sceneShape(b), toVec3(b.position), toQuat(b.orientation));
    boxes.push_back({(a.lo.x() - frame.origin.x) / frame.cell_size,
                     (a.lo.z() - frame.origin.y) / frame.cell_size,
                     (a.hi.x() - frame.origin.x) / frame.cell_size,
                     (a.hi.z() - frame.origin.y) / frame.cell_size});
  }
  return boxes;
}

ai::NavMeshConfig navMeshConfig(const Scene& scene, const crowd::MapFrame& frame) {
  ai::NavMeshConfig c;
  c.agent_radius = scene.map.agent_radius / frame.cell_size;
  return c;
}

std::vector<ai::NavBox> navMeshBoxes(const Scene& scene, const crowd::MapFrame& frame) {
  return scene.map.static_bodies ? staticFootprints(scene, frame) : std::vector<ai::NavBox>{};
}

}  // namespace zonesim::zone
