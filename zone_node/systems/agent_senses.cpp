#include "zone_node/systems/agent_senses.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "zone_node/ghost_store.h"
#include "zone_node/systems/nearest_grid.h"

namespace zonesim::zone {

namespace {

struct Enemy {
  EntityId id;
  double x, z;
};

bool isEnemy(EntityKind kind, std::int32_t agent_type) {
  return kind == EntityKind::Avatar || (kind == EntityKind::Npc && agent_type < 0);
}

}  // namespace

void senseAgents(const AgentSettings& settings, const EntityStore& store, const GhostStore* ghosts,
                 double time, std::span<const std::uint8_t> decides,
                 std::vector<AgentSenses>& out) {
  out.assign(store.size(), AgentSenses{});
  const auto looks = [&](std::size_t i) { return decides.empty() || decides[i] != 0; };
  bool anyone_looks = false;
  for (std::size_t i = 0; i < store.size() && !anyone_looks; ++i)
    anyone_looks = store.agent[i].type >= 0 && looks(i);
  double sight = 0;
  for (const AgentType& t : settings.types) sight = std::max(sight, t.sight);
  NearestGrid<Enemy> grid(std::max(sight, 1.0));
  if (sight > 0 && anyone_looks) {
    for (std::size_t i = 0; i < store.size(); ++i)
      if (isEnemy(store.kind[i], store.agent[i].type))
        grid.add({store.id[i], store.pos[i].x(), store.pos[i].z()});
    if (ghosts) {
      const std::optional<std::size_t> type = ghosts->columnIndex(kAgentType);
      for (std::size_t i = 0; i < ghosts->size(); ++i)
        if (isEnemy(ghosts->kind[i], type ? std::int32_t(ghosts->value(*type, i)) : -1))
          grid.add({ghosts->id[i], ghosts->pos[i].x(), ghosts->pos[i].z()});
    }
  }
  for (std::size_t i = 0; i < store.size(); ++i) {
    const AgentData& a = store.agent[i];
    if (a.type < 0) continue;
    const AgentType& type = settings.types[std::size_t(a.type)];
    AgentSenses& s = out[i];
    if (looks(i)) {
      double d = kNoEnemy;
      const Enemy* e = type.sight > 0 ? grid.nearest(
                                            store.pos[i].x(), store.pos[i].z(), type.sight,
                                            [](const Enemy&) { return true; }, d)
                                      : nullptr;
      s.enemy_seen = e != nullptr;
      if (s.enemy_seen) s.enemy = Vec3(e->x, store.pos[i].y(), e->z);
      s.value[int(AgentSense::EnemyDistance)] = s.enemy_seen ? d : kNoEnemy;
    } else {
      s.enemy_seen = a.enemy_seen;
      if (s.enemy_seen) s.enemy = Vec3(a.enemy_x, store.pos[i].y(), a.enemy_z);
      s.value[int(AgentSense::EnemyDistance)] = a.enemy_distance;
    }
    s.value[int(AgentSense::Health)] = a.health;
    s.value[int(AgentSense::Energy)] = a.energy;
    s.value[int(AgentSense::Arrived)] = a.nav == 3 ? 1.0 : 0.0;
    s.value[int(AgentSense::Time)] = time;
  }
}

}  // namespace zonesim::zone
