#include "zone_node/formation_start.h"

#include <algorithm>

#include "common/scene.h"
#include "zone_node/world_map.h"

namespace zonesim::zone {

crowd::FormationSettings formationSettings(const NpcFormation& f) {
  crowd::FormationSettings s;
  s.centre_speed = f.centre_speed;
  s.member_max_speed = f.max_speed;
  s.max_force = f.max_force;
  s.steer_rate = f.steer_rate;
  s.slot_gain = f.slot_gain;
  s.slow_radius = f.slow_radius;
  s.turn_rate = f.turn_rate;
  s.cut_off_distance = f.cut_off;
  s.rejoin_distance = f.rejoin;
  s.replan_distance = f.replan;
  s.separation_radius = f.separation_radius;
  s.separation_weight = f.separation_weight;
  return s;
}

crowd::Vec2 formationHeading(const NpcFormation& f) {
  if (f.route.size() < 2) return {1.0, 0.0};
  crowd::Vec2 d{f.route[1].x - f.route[0].x, f.route[1].z - f.route[0].z};
  return crowd::lengthSq(d) > 1e-12 ? crowd::withLength(d, 1.0) : crowd::Vec2{1.0, 0.0};
}

crowd::Vec2 formationSlot(const NpcFormation& f, int count, int k) {
  const int columns = std::min(f.columns, std::max(count, 1));
  const int rows = (count + columns - 1) / columns;
  const int row = k / columns, col = k % columns;
  const int inRow = std::min(columns, count - row * columns);
  return {(0.5 * (rows - 1) - row) * f.spacing, (0.5 * (inRow - 1) - col) * f.spacing};
}

crowd::Vec2 formationStart(const Scene& scene, const WorldMap& map, std::size_t p, int k) {
  const NpcFormation& f = scene.npcs[p].formation;
  crowd::FormationCentre centre(formationSettings(f), {f.route[0].x, f.route[0].z},
                                formationHeading(f));
  crowd::Vec2 at = centre.slotPosition(formationSlot(f, scene.npcs[p].count, k));
  return map.walkable(at.x, at.y) ? at : centre.position();
}

}  // namespace zonesim::zone
