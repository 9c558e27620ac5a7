#include "common/scene_crowd.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>

namespace zonesim {

void readObstacleMap(const SceneMap& root, const std::string& file, Scene& scene) {
  std::optional<SceneNode> node = root.optional("map");
  if (!node) return;
  SceneMap m = node->map({"file", "origin", "cell_size"});
  SceneNode file_node = m.required("file");
  std::string name = file_node.text();
  if (name.empty()) file_node.fail("must not be empty");
  std::filesystem::path path(name);
  if (path.is_relative()) path = std::filesystem::path(file).parent_path() / path;
  // Only whether it opens here: its cells are parsed by zone_node/world_map.h, which reports
  // the map's own file:line, and checks that the grid fits in the world.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec) || !std::ifstream(path)) {
    file_node.fail("cannot open map file '" + path.string() + "'");
  }
  ObstacleMap& map = scene.map;
  map.file = path.lexically_normal().string();
  map.line = file_node.line();
  map.origin_x = scene.world.min.x;
  map.origin_z = scene.world.min.z;
  if (std::optional<SceneNode> origin = m.optional("origin")) {
    SceneVec3 at = origin->vec3();  // [x, y, z] like every point in a scene; y is ignored
    if (at.x < scene.world.min.x || at.x > scene.world.max.x || at.z < scene.world.min.z ||
        at.z > scene.world.max.z)
      origin->fail("x, z (" + formatNumber(at.x) + ", " + formatNumber(at.z) +
                   ") is outside the world");
    map.origin_x = at.x;
    map.origin_z = at.z;
  }
  m.read("cell_size", map.cell_size, Limit::above(0));
}

}  // namespace zonesim
