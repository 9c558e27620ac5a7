#pragma once
// The scene's obstacle map (`map:` key) loaded for the zone systems: the grid and where it lies
// on the ground plane. Every rank loads the same file, so every rank sees the same walls.

#include <memory>

#include "ai/grid_map.h"
#include "crowd/map_frame.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::zone {

/// A grid map placed in the world: `frame` maps world (x, z) to cells (Vec2 x = world x,
/// Vec2 y = world z).
struct WorldMap {
  ai::GridMap grid;
  crowd::MapFrame frame;

  /// True when world point (x, z) lies on a passable cell.
  bool walkable(double x, double z) const { return crowd::walkable(grid, frame, {x, z}); }
};

/// The scene's map, or null when the scene has none. Throws SceneError "mapfile:line: map:
/// ..." for a malformed map file, and "scene:line: map.file: ..." when the grid reaches past
/// the world on x or z.
std::shared_ptr<const WorldMap> loadWorldMap(const Scene& scene);

}  // namespace zonesim::zone
