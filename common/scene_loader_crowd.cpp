#include "common/scene_loader_crowd.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "common/scene.h"

namespace zonesim {

namespace {

// `map.doors`: cells that open or close at scene times, in time order. Whether each cell lies on
// the grid is checked by the zone, which parses the map file (zone_node/world_map.h).
void readMapDoors(const SceneMap& m, ObstacleMap& map) {
  std::optional<SceneNode> doors = m.optional("doors");
  if (!doors) return;
  for (const SceneNode& item : doors->items()) {
    SceneMap d_map = item.map({"at_s", "cell", "open"});
    MapDoor d;
    d.at_s = d_map.required("at_s").number(Limit::atLeast(0));
    SceneNode cell = d_map.required("cell");
    std::vector<SceneNode> xy = cell.items();
    if (xy.size() != 2) cell.fail("must be [x, y] (map column and row)");
    d.x = xy[0].integer(Limit::atLeast(0));
    d.y = xy[1].integer(Limit::atLeast(0));
    d_map.read("open", d.open);
    d.file = item.file();
    d.line = item.line();
    if (!map.doors.empty() && d.at_s < map.doors.back().at_s)
      d_map.failAt("at_s", "doors must be listed in time order");
    map.doors.push_back(d);
  }
}

}  // namespace

void readObstacleMap(const SceneMap& root, Scene& scene) {
  std::optional<SceneNode> node = root.optional("map");
  if (!node) return;
  SceneMap m = node->map({"file", "origin", "cell_size", "doors", "fields", "navigation",
                          "agent_radius", "static_bodies"});
  SceneNode file_node = m.required("file");
  std::string name = file_node.text();
  if (name.empty()) file_node.fail("must not be empty");
  std::filesystem::path path(name);
  // Relative to the file that names it (an overlay's own, if it changed the map).
  if (path.is_relative()) path = std::filesystem::path(file_node.file()).parent_path() / path;
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
  if (std::optional<SceneNode> fields = m.optional("fields")) {
    std::string fields_name = fields->text();
    if (fields_name.empty()) fields->fail("must not be empty");
    std::filesystem::path fields_path(fields_name);
    if (fields_path.is_relative())
      fields_path = std::filesystem::path(fields->file()).parent_path() / fields_path;
    map.fields = fields_path.lexically_normal().string();
    map.fields_line = fields->line();
  }
  map.navigation = m.choice("navigation", {"grid", "hpa", "navmesh", "jps"}, -1);
  if (std::optional<SceneNode> nav = m.optional("navigation")) map.navigation_line = nav->line();
  // What only the navigation mesh honours: refused elsewhere rather than silently ignored.
  for (const char* key : {"agent_radius", "static_bodies"}) {
    if (map.navigation != ObstacleMap::kNavMesh && m.optional(key)) {
      m.failAt(key, "applies to map.navigation: navmesh only");
    }
  }
  m.read("agent_radius", map.agent_radius, Limit::atLeast(0));
  m.read("static_bodies", map.static_bodies);
  readMapDoors(m, map);
}

namespace {

// A point [x, y, z] inside the world's ground rectangle (y is ignored), as (x, z).
std::pair<double, double> groundPoint(const SceneNode& node, const Scene& scene) {
  SceneVec3 at = node.vec3();
  if (at.x < scene.world.min.x || at.x > scene.world.max.x || at.z < scene.world.min.z ||
      at.z > scene.world.max.z)
    node.fail("x, z (" + formatNumber(at.x) + ", " + formatNumber(at.z) + ") is outside the world");
  return {at.x, at.z};
}

}  // namespace

void readFlockGoal(const SceneMap& flock, const Scene& scene, NpcFlock& f) {
  f.goal_speed = f.max_speed;
  if (!flock.optional("goal")) return;
  SceneMap m = flock.section("goal", {"point", "weight", "speed", "slow_radius"});
  f.has_goal = true;
  std::tie(f.goal_x, f.goal_z) = groundPoint(m.required("point"), scene);
  m.read("weight", f.goal_weight, Limit::atLeast(0));
  m.read("speed", f.goal_speed, Limit::above(0));
  m.read("slow_radius", f.goal_slow_radius, Limit::above(0));
  if (f.goal_speed > f.max_speed) {
    m.failAt("speed", formatNumber(f.goal_speed) + " m/s is above flock.max_speed (" +
                          formatNumber(f.max_speed) + " m/s)");
  }
}

void readCrowdLod(const SceneMap& root, Scene& scene) {
  if (!root.optional("lod")) return;
  CrowdLod& l = scene.lod;
  l.enabled = true;  // a section that is there means on, unless it says enabled: false
  SceneMap m =
      root.section("lod", {"enabled", "near_radius", "far_radius", "mid_every", "far_every",
                           "mid_steers", "far_steers", "observers", "crowded_count", "crowded_cell",
                           "physics_every", "physics_max_step"});
  m.read("enabled", l.enabled);
  m.read("near_radius", l.near_radius, Limit::atLeast(0));
  m.read("far_radius", l.far_radius, Limit::atLeast(l.near_radius));
  m.read("mid_every", l.mid_every, Limit::between(1, 64));
  m.read("far_every", l.far_every, Limit::between(1, 64));
  m.read("mid_steers", l.mid_steers);
  m.read("far_steers", l.far_steers);
  m.read("crowded_count", l.crowded_count, Limit::between(0, 1000000));
  m.read("crowded_cell", l.crowded_cell, Limit::above(0));
  m.read("physics_every", l.physics_every, Limit::between(1, 64));
  m.read("physics_max_step", l.physics_max_step, Limit::atLeast(0));
  // A cell's count includes agents across a border, which a zone sees only as ghosts.
  if (l.crowded_count > 0 && scene.zones.columns * scene.zones.rows > 1 &&
      l.crowded_cell > scene.halo_width) {
    m.failAt("crowded_cell", formatNumber(l.crowded_cell) + " m is wider than halo.width (" +
                                 formatNumber(scene.halo_width) +
                                 " m): cells across a border would count differently per zone");
  }
  if (std::optional<SceneNode> list = m.optional("observers")) {
    for (const SceneNode& item : list->items()) l.observers.push_back(groundPoint(item, scene));
  }
}

ScenePoint readGroundPoint(const SceneNode& node, const Scene& scene) {
  SceneVec3 at = node.vec3();  // [x, y, z] like every point in a scene; y is ignored
  if (at.x < scene.world.min.x || at.x > scene.world.max.x || at.z < scene.world.min.z ||
      at.z > scene.world.max.z)
    node.fail("x, z (" + formatNumber(at.x) + ", " + formatNumber(at.z) + ") is outside the world");
  return {at.x, at.z, node.line()};
}

void readNpcFlow(const SceneMap& population, const Scene& scene, NpcPopulation& p) {
  if (!population.optional("flow")) return;
  for (const char* other : {"separation", "gather", "flock"}) {
    if (population.optional(other)) {
      population.failAt(other, "a flow-field population follows its fields, not this");
    }
  }
  NpcFlow& f = p.flow;
  f.enabled = true;
  SceneMap m =
      population.section("flow", {"destinations", "max_speed", "max_force", "steer_rate",
                                  "separation", "arrive_radius", "slow_radius", "body_radius"});
  if (!scene.map.present()) {
    m.failAt("destinations", "a flow-field population needs the scene's map: key");
  }
  SceneNode list = m.required("destinations");
  std::vector<SceneNode> items = list.items();
  if (items.empty()) list.fail("needs at least one destination");
  if (items.size() > 256) list.fail("at most 256 destinations (one field each)");
  for (const SceneNode& item : items) {
    SceneVec3 at = item.vec3();  // [x, y, z]; y is ignored
    if (at.x < scene.world.min.x || at.x > scene.world.max.x || at.z < scene.world.min.z ||
        at.z > scene.world.max.z)
      item.fail("x, z (" + formatNumber(at.x) + ", " + formatNumber(at.z) +
                ") is outside the world");
    f.destinations.push_back({at.x, at.z, item.line()});
  }
  m.read("max_speed", f.max_speed, Limit::above(0));
  m.read("max_force", f.max_force, Limit::above(0));
  m.read("steer_rate", f.steer_rate, Limit::above(0));
  m.read("arrive_radius", f.arrive_radius, Limit::above(0));
  m.read("slow_radius", f.slow_radius, Limit::above(0));
  readSeparation(m, scene, f.separation_radius, f.separation_weight);
  readBodyRadius(m, scene, f.body_radius);
}

void readBodyRadius(const SceneMap& m, const Scene& scene, double& radius) {
  m.read("body_radius", radius, Limit::atLeast(0));
  // The halo must show more than the two bodies themselves (crowd/keep_apart.h).
  if (radius > 0 && 2 * radius >= scene.halo_width) {
    m.failAt("body_radius", formatNumber(radius) + " m: twice it must be less than halo.width (" +
                                formatNumber(scene.halo_width) + " m)");
  }
}

void readSeparation(const SceneMap& m, const Scene& scene, double& radius, double& weight) {
  SceneMap sep = m.section("separation", {"radius", "weight"});
  sep.read("radius", radius, Limit::atLeast(0));
  sep.read("weight", weight, Limit::atLeast(0));
  if (radius > scene.halo_width) {
    sep.failAt("radius", formatNumber(radius) + " m is wider than halo.width (" +
                             formatNumber(scene.halo_width) + " m)");
  }
}

}  // namespace zonesim
