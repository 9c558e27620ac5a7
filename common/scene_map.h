#pragma once
// The scene's `map` key: the obstacle grid laid on the ground plane, and its doors.

#include <string>
#include <vector>

namespace zonesim {

/// A map cell that opens or closes at a scene time (`map.doors`).
struct MapDoor {
  double at_s = 0;   ///< simulated seconds
  int x = 0, y = 0;  ///< cell of the scene's map
  bool open = false;
  std::string file;  ///< scene file, for the zone's check that the cell is on the map
  int line = 0;      ///< its line
};

/// The world's obstacle map: a Moving AI .map grid laid on the ground plane (`map:` key).
/// Column x runs along world x, row y along world z. Loaded by zone_node/world_map.h.
struct ObstacleMap {
  std::string file;            ///< path resolved against the scene file's folder; empty: no map
  double origin_x = 0;         ///< world x of the outer corner of cell (0, 0)
  double origin_z = 0;         ///< world z of the outer corner of cell (0, 0)
  double cell_size = 1;        ///< side of one cell, metres
  int line = 0;                ///< line of `map.file` in the scene (for errors found on loading)
  std::vector<MapDoor> doors;  ///< in time order; agents' paths and flow crowds see them
  /// Flow fields built beforehand for this map (bake_fields), resolved like `file`; empty:
  /// the zones build them at start. Opened and checked by the zone (it may not exist yet when
  /// bake_fields reads the scene to write it).
  std::string fields;
  int fields_line = 0;  ///< line of `map.fields` in the scene
  /// `map.navigation`: 0 grid (A*), 1 hpa, 2 navmesh, 3 jps; -1 when absent, so that
  /// `agents.paths.planner` decides (common/scene_loader_agents.cpp).
  int navigation = -1;
  int navigation_line = 0;  ///< its line
  static constexpr int kNavMesh = 2;  ///< `navigation`'s value for navmesh
  /// `map.agent_radius` (m): the navigation mesh keeps this clearance from walls (navmesh only).
  double agent_radius = 0;
  /// `map.static_bodies`: the navigation mesh also closes the cells under the scene's static
  /// bodies (physics.bodies with motion: static; navmesh only).
  bool static_bodies = false;
  /// Whether the scene has a map.
  bool present() const { return !file.empty(); }
};

}  // namespace zonesim
