#include "zone_node/zone_map.h"

#include <string>
#include <utility>

#include "common/scene.h"

namespace zonesim::zone {

std::unique_ptr<ZoneMap> ZoneMap::load(const Scene& scene) {
  std::shared_ptr<const WorldMap> map = loadWorldMap(scene);
  if (!map) return nullptr;
  return std::make_unique<ZoneMap>(*map, scene.map.doors);
}

ZoneMap::ZoneMap(WorldMap map, const std::vector<MapDoor>& doors)
    : map_(std::move(map)), doors_(doors) {
  const ai::GridMap& g = map_.grid;
  for (const MapDoor& d : doors_)
    if (!g.inside(d.x, d.y))
      throw SceneError(d.file + ":" + std::to_string(d.line) + ": map.doors: cell (" +
                       std::to_string(d.x) + ", " + std::to_string(d.y) + ") is off the " +
                       std::to_string(g.width()) + "x" + std::to_string(g.height()) + " map");
}

std::span<const ZoneMap::DoorChange> ZoneMap::applyDoors(double time) {
  now_.clear();
  while (next_door_ < doors_.size() && doors_[next_door_].at_s <= time + 1e-9) {
    const MapDoor& d = doors_[next_door_++];
    const bool changed = map_.grid.passable(d.x, d.y) != d.open;
    if (changed) map_.grid.setPassable(d.x, d.y, d.open);
    now_.push_back({&d, changed});
  }
  return now_;
}

bool ZoneMap::changedNow() const {
  for (const DoorChange& c : now_)
    if (c.changed) return true;
  return false;
}

}  // namespace zonesim::zone
