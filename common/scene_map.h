#pragma once
// The scene's `map` key: the obstacle grid laid on the ground plane, and its doors.

#include <string>
#include <vector>

namespace zonesim {

/// The world's obstacle map: a Moving AI .map grid laid on the ground plane (`map:` key).
/// Column x runs along world x, row y along world z. Loaded by zone_node/world_map.h.
struct ObstacleMap {
  std::string file;      ///< path resolved against the scene file's folder; empty: no map
  double origin_x = 0;   ///< world x of the outer corner of cell (0, 0)
  double origin_z = 0;   ///< world z of the outer corner of cell (0, 0)
  double cell_size = 1;  ///< side of one cell, metres
  int line = 0;          ///< line of `map.file` in the scene (for errors found on loading)
  /// Whether the scene has a map.
  bool present() const { return !file.empty(); }
};

}  // namespace zonesim
