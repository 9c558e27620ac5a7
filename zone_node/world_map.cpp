#include "zone_node/world_map.h"

#include <cmath>
#include <string>

#include "ai/parse_error.h"
#include "common/scene.h"
#include "common/scene_source.h"

namespace zonesim::zone {
namespace {

std::string number(double v) {
  std::string s = std::to_string(v);
  s.erase(s.find_last_not_of('0') + 1);
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

}  // namespace

std::shared_ptr<const WorldMap> loadWorldMap(const Scene& scene) {
  if (!scene.map.present()) return nullptr;
  auto map = std::make_shared<WorldMap>();
  try {
    map->grid = ai::loadMovingAiMap(scene.map.file);
  } catch (const ai::ParseError& e) {
    // ParseError already reads "mapfile:line: what"; name the field like every scene error.
    std::string what = e.what();
    std::string prefix = e.file() + ":" + std::to_string(e.line()) + ": ";
    throw SceneError(prefix + "map: " + what.substr(prefix.size()));
  }
  map->frame.origin = crowd::Vec2{scene.map.origin_x, scene.map.origin_z};
  map->frame.cell_size = scene.map.cell_size;
  double max_x = scene.map.origin_x + map->grid.width() * scene.map.cell_size;
  double max_z = scene.map.origin_z + map->grid.height() * scene.map.cell_size;
  // A small tolerance: a 1e-12 overshoot from a cell size like 0.1 is not a user mistake.
  double slack = 1e-9 * (1 + std::abs(max_x) + std::abs(max_z));
  if (max_x > scene.world.max.x + slack || max_z > scene.world.max.z + slack) {
    throw SceneError(sceneFile(scene) + ":" + std::to_string(scene.map.line) +
                     ": map.file: " + std::to_string(map->grid.width()) + " x " +
                     std::to_string(map->grid.height()) + " cells of " +
                     number(scene.map.cell_size) + " m reach (" + number(max_x) + ", " +
                     number(max_z) + "), past the world's max x, z (" + number(scene.world.max.x) +
                     ", " + number(scene.world.max.z) + ")");
  }
  return map;
}

}  // namespace zonesim::zone
