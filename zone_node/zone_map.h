#pragma once
// The zone's obstacle map as the scene's doors leave it. One copy, owned by the zone and changed
// once per tick at the start of the AI phase, which every system reads: agents plan paths on it,
// flow crowds rebuild their fields from it, formation members and ants walk on it. (Each kept a
// copy of its own once, and formations and ants never saw a door.)

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "common/scene_map.h"
#include "zone_node/world_map.h"

namespace zonesim {
struct Scene;
}

namespace zonesim::zone {

class ZoneMap {
 public:
  /// A door due this tick, and whether it changed its cell (it may already have been so).
  struct DoorChange {
    const MapDoor* door;
    bool changed;
  };

  /// The scene's map with its doors, or null when the scene has no map. Throws SceneError as
  /// loadWorldMap does, and "file:line: doors: cell (x, y) is off the WxH map".
  static std::unique_ptr<ZoneMap> load(const Scene& scene);
  ZoneMap(WorldMap map, const std::vector<MapDoor>& doors);

  /// The map as the doors have left it so far.
  const WorldMap& world() const { return map_; }
  /// The same grid, for the path service, which repairs its planner when told of a change
  /// (ai::PathService::cellChanged) but never changes the grid itself here.
  ai::GridMap& serviceGrid() { return map_.grid; }
  /// Whether the scene has doors at all.
  bool hasDoors() const { return !doors_.empty(); }

  /// Opens and closes the doors due by simulated time `time` (in scene order); returns them.
  std::span<const DoorChange> applyDoors(double time);
  /// The doors applied by the last applyDoors (none before the first).
  std::span<const DoorChange> doorsNow() const { return now_; }
  /// Whether one of them changed a cell.
  bool changedNow() const;

 private:
  WorldMap map_;
  std::vector<MapDoor> doors_;  // in time order
  std::size_t next_door_ = 0;
  std::vector<DoorChange> now_;
};

}  // namespace zonesim::zone
