// The `formation` block of an NPC population (docs/scene-format.md): a fixed group on the
// scene's map whose centre walks a route of points.

#include "common/scene.h"
#include "common/scene_loader_crowd.h"

namespace zonesim {

void readNpcFormation(const SceneMap& population, const Scene& scene, NpcPopulation& p) {
  if (!population.optional("formation")) return;
  for (const char* other : {"separation", "gather", "flock", "flow", "colony"}) {
    if (population.optional(other))
      population.failAt(other, "a formation population holds its slots, not this");
  }
  NpcFormation& f = p.formation;
  f.enabled = true;
  SceneMap m =
      population.section("formation", {"route", "columns", "spacing", "centre_speed", "max_speed",
                                       "max_force", "steer_rate", "slot_gain", "slow_radius",
                                       "turn_rate", "cut_off", "rejoin", "replan", "separation"});
  if (!scene.map.present()) m.failAt("route", "a formation needs the scene's map: key");
  SceneNode list = m.required("route");
  std::vector<SceneNode> items = list.items();
  if (items.empty()) list.fail("needs at least one point (where the centre starts)");
  if (items.size() > 1024) list.fail("at most 1024 points");
  for (const SceneNode& item : items) f.route.push_back(readGroundPoint(item, scene));
  m.read("columns", f.columns, Limit::between(1, 64));
  m.read("spacing", f.spacing, Limit::above(0));
  m.read("centre_speed", f.centre_speed, Limit::above(0));
  m.read("max_speed", f.max_speed, Limit::above(0));
  m.read("max_force", f.max_force, Limit::above(0));
  m.read("steer_rate", f.steer_rate, Limit::above(0));
  m.read("slot_gain", f.slot_gain, Limit::above(0));
  m.read("slow_radius", f.slow_radius, Limit::above(0));
  m.read("turn_rate", f.turn_rate, Limit::above(0));
  m.read("cut_off", f.cut_off, Limit::above(0));
  m.read("rejoin", f.rejoin, Limit::above(0));
  m.read("replan", f.replan, Limit::above(0));
  // Members catch up with their slots only if they are faster than the centre.
  if (f.max_speed <= f.centre_speed) {
    m.failAt("max_speed", formatNumber(f.max_speed) + " m/s is not above centre_speed (" +
                              formatNumber(f.centre_speed) + " m/s)");
  }
  if (f.rejoin >= f.cut_off) {
    m.failAt("rejoin", formatNumber(f.rejoin) + " m is not below cut_off (" +
                           formatNumber(f.cut_off) + " m)");
  }
  readSeparation(m, scene, f.separation_radius, f.separation_weight);
}

}  // namespace zonesim
