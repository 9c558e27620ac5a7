#include "zone_node/systems/agent_senses.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "zone_node/ghost_store.h"

namespace zonesim::zone {

namespace {

struct Enemy {
  EntityId id;
  double x, z;
};

bool isEnemy(EntityKind kind, std::int32_t agent_type) {
  return kind == EntityKind::Avatar || (kind == EntityKind::Npc && agent_type < 0);
}

/// Enemies bucketed in square cells as wide as the widest sight: a query reads 3x3 cells.
class EnemyGrid {
 public:
  explicit EnemyGrid(double cell) : cell_(cell) {}
  void add(const Enemy& e) { cells_[key(cell(e.x), cell(e.z))].push_back(e); }
  /// Nearest enemy within `radius` of (x, z); lowest id on a tie. False when none.
  bool nearest(double x, double z, double radius, Enemy& out, double& dist) const {
    bool found = false;
    std::int64_t cx = cell(x), cz = cell(z);
    for (std::int64_t i = cx - 1; i <= cx + 1; ++i) {
      for (std::int64_t k = cz - 1; k <= cz + 1; ++k) {
        auto it = cells_.find(key(i, k));
        if (it == cells_.end()) continue;
        for (const Enemy& e : it->second) {
          double d = std::hypot(e.x - x, e.z - z);
          if (d > radius) continue;
          if (!found || d < dist || (d == dist && e.id < out.id)) {
            out = e;
            dist = d;
            found = true;
          }
        }
      }
    }
    return found;
  }

 private:
  std::int64_t cell(double v) const { return std::int64_t(std::floor(v / cell_)); }
  static std::int64_t key(std::int64_t x, std::int64_t z) { return x * 4000037 + z; }
  double cell_;
  std::unordered_map<std::int64_t, std::vector<Enemy>> cells_;  // looked up, never iterated
};

}  // namespace

void senseAgents(const AgentSettings& settings, const EntityStore& store, const GhostStore* ghosts,
                 double time, std::vector<AgentSenses>& out) {
  out.assign(store.size(), AgentSenses{});
  double sight = 0;
  for (const AgentType& t : settings.types) sight = std::max(sight, t.sight);
  EnemyGrid grid(std::max(sight, 1.0));
  if (sight > 0) {
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
    Enemy e{};
    double d = kNoEnemy;
    s.enemy_seen =
        type.sight > 0 && grid.nearest(store.pos[i].x(), store.pos[i].z(), type.sight, e, d);
    if (s.enemy_seen) s.enemy = Vec3(e.x, store.pos[i].y(), e.z);
    s.value[int(AgentSense::EnemyDistance)] = s.enemy_seen ? d : kNoEnemy;
    s.value[int(AgentSense::Health)] = a.health;
    s.value[int(AgentSense::Energy)] = a.energy;
    s.value[int(AgentSense::Arrived)] = a.nav == 3 ? 1.0 : 0.0;
    s.value[int(AgentSense::Time)] = time;
  }
}

}  // namespace zonesim::zone
