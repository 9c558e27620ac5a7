#include "zone_node/systems/flow_movement.h"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/scene.h"
#include "common/scene_source.h"
#include "common/splitmix.h"
#include "crowd/flow_crowd.h"
#include "crowd/flow_field_file.h"
#include "zone_node/ghost_store.h"
#include "zone_node/systems/crowd_lod.h"
#include "zone_node/systems/navmesh_obstacles.h"
#include "zone_node/systems/planar_crowd.h"
#include "zone_node/tick_profile.h"
#include "zone_node/world_map.h"
#include "zone_node/zone_map.h"

namespace zonesim::zone {

/// One flow population: its crowd (fields shared by all its NPCs) and the gather buffers.
struct FlowMovement::Group {
  Group(std::int32_t p, const ai::GridMap& grid, const crowd::MapFrame& frame,
        const crowd::FlowCrowdSettings& s, const crowd::LodSettings& l)
      : view(p), crowd(grid, frame, s), lod(l) {}
  PlanarCrowd view;
  crowd::FlowCrowd crowd;
  crowd::LevelOfDetail lod;
  std::vector<std::uint16_t> dest;
  std::vector<std::uint8_t> arrived;
  std::vector<std::uint8_t> walking;    // per agent: counts toward crowding
  std::vector<std::uint32_t> crowding;  // per agent: its cell's count (empty: not used)
  // Asleep: no NPC of the population in this zone walked at the end of a step, and the store
  // had this membership then (a stamp no other store shares). Arrived NPCs stand still, so
  // until an entity comes or goes the step would find the same and change nothing.
  bool asleep = false;
  std::uint64_t slept_at = 0;
  bool sleepsIn(const EntityStore& store) const { return asleep && slept_at == store.membership(); }
  void fallAsleepIn(const EntityStore& store) {
    asleep = true;
    slept_at = store.membership();
  }
};

int flowDestination(std::uint64_t id, int count) {
  // Mixed: consecutive ids spread evenly over the destinations.
  return int(splitmix64(id) % std::uint64_t(count));
}

namespace {

crowd::FlowCrowdSettings settingsOf(const Scene& scene, const NpcFlow& f, const WorldMap& map) {
  crowd::FlowCrowdSettings s;
  s.max_speed = f.max_speed;
  s.max_force = f.max_force;
  s.steer_rate = f.steer_rate;
  s.separation_radius = f.separation_radius;
  s.separation_weight = f.separation_weight;
  s.arrive_radius = f.arrive_radius;
  s.slow_radius = f.slow_radius;
  s.grid_cell = std::max(2.0, f.separation_radius);  // the same on every rank: fixes sum order
  s.body_radius = f.body_radius;
  s.sight = scene.halo_width;  // every neighbour that could bind a body is a ghost on every rank
  // map.navigation: navmesh: agents aim at the funnelled mesh path's first corner, on the mesh
  // the agents' planner builds (the same clearance and static bodies).
  s.navmesh = scene.map.navigation == ObstacleMap::kNavMesh;
  if (s.navmesh) {
    s.navmesh_config = navMeshConfig(scene, map.frame);
    s.navmesh_boxes = navMeshBoxes(scene, map.frame);
  }
  return s;
}

}  // namespace

FlowMovement::FlowMovement(const Scene& scene, const ZoneMap* zone_map)
    : map_(zone_map), lod_(scene.lod.enabled) {
  const WorldMap* map = zone_map ? &zone_map->world() : nullptr;
  // Fields baked into a file (map.fields) are loaded once and handed to every population
  // heading to their goals; without it each field is built here.
  std::vector<std::unique_ptr<crowd::FlowField>> baked;
  const std::string fields_at =
      sceneFile(scene) + ":" + std::to_string(scene.map.fields_line) + ": map.fields: ";
  if (map && !scene.map.fields.empty()) {
    try {
      baked = crowd::readFlowFields(scene.map.fields, map->grid);
    } catch (const std::runtime_error& e) {
      throw SceneError(fields_at + e.what());
    }
  }
  for (std::size_t p = 0; p < scene.npcs.size(); ++p) {
    const NpcFlow& f = scene.npcs[p].flow;
    if (!f.enabled) continue;
    if (!map) throw SceneError(sceneFile(scene) + ":0: map: a flow population needs a map");
    auto g = std::make_unique<Group>(std::int32_t(p), map->grid, map->frame,
                                     settingsOf(scene, f, *map), lodOf(scene.lod));
    for (std::size_t k = 0; k < f.destinations.size(); ++k) {
      const NpcFlow::Destination& d = f.destinations[k];
      if (!map->walkable(d.x, d.z)) {
        throw SceneError(sceneFile(scene) + ":" + std::to_string(d.line) + ": populations[" +
                         std::to_string(p) + "].flow.destinations[" + std::to_string(k) +
                         "]: lies on a blocked cell of the map");
      }
      const ai::Cell goal = map->frame.cellOf({d.x, d.z});
      const std::string where = sceneFile(scene) + ":" + std::to_string(d.line) + ": populations[" +
                                std::to_string(p) + "].flow.destinations[" + std::to_string(k) +
                                "]: ";
      // With navmesh, a goal off the mesh (under a static body) is refused by name.
      auto add = [&](auto&& destination) {
        try {
          g->crowd.addDestination(std::forward<decltype(destination)>(destination));
        } catch (const std::invalid_argument& e) {
          throw SceneError(where + e.what() + " (under a static body: map.static_bodies)");
        }
      };
      if (scene.map.fields.empty()) {
        add(goal);
        continue;
      }
      auto it = std::find_if(baked.begin(), baked.end(), [&](const auto& f) {
        return f->goal().x == goal.x && f->goal().y == goal.y;
      });
      if (it == baked.end()) {
        throw SceneError(fields_at + scene.map.fields + " has no field for populations[" +
                         std::to_string(p) + "].flow.destinations[" + std::to_string(k) +
                         "] (cell " + std::to_string(goal.x) + ", " + std::to_string(goal.y) +
                         "); build it again with bake_fields");
      }
      add(std::make_unique<crowd::FlowField>(**it));
    }
    groups_.push_back(std::move(g));
    reach_ = std::max(reach_, f.separation_radius);
  }
}

FlowMovement::~FlowMovement() = default;

const ai::GridMap* FlowMovement::grid() const {
  return groups_.empty() ? nullptr : &map_->world().grid;
}

int FlowMovement::followDoors() {
  // Every rank's map changes alike, so every rank rebuilds the same fields.
  if (groups_.empty() || !map_->changedNow()) return 0;
  int rebuilt = 0;
  for (const auto& g : groups_) rebuilt += g->crowd.refreshFields();
  return rebuilt;
}

FlowMovement::Group* FlowMovement::groupOf(std::int32_t population) const {
  for (const auto& g : groups_)
    if (g->view.population == population) return g.get();
  return nullptr;
}

bool FlowMovement::arrived(const EntityStore& store, std::size_t i) const {
  Group* g = groupOf(store.npc[i].population);
  if (!g) return false;
  int d = flowDestination(store.id[i].value, g->crowd.destinationCount());
  return g->crowd.hasArrived({store.pos[i].x(), store.pos[i].z()}, d);
}

void FlowMovement::step(StepContext& ctx) {
  fields_rebuilt_ = followDoors();
  walking_ = advance(ctx.store, ctx.ghosts, ctx.dt, ctx.players, std::int64_t(ctx.tick));
  ctx.counters.flow_npcs_visited = visited_;
}

std::size_t FlowMovement::advance(EntityStore& store, const GhostStore* ghosts, double dt,
                                  std::span<const crowd::Vec2> players, std::int64_t tick) {
  std::size_t walking = 0;
  updates_ = visited_ = sleeping_ = 0;
  arrived_now_.clear();
  for (const std::unique_ptr<Group>& gp : groups_) {
    Group& g = *gp;
    if (g.sleepsIn(store)) {
      ++sleeping_;
      continue;
    }
    g.asleep = false;
    const int count = g.crowd.destinationCount();
    g.view.gatherAgents(store);
    visited_ += g.view.ids.size();
    g.dest.clear();
    g.arrived.clear();
    for (std::size_t a = 0; a < g.view.ids.size(); ++a) {
      int d = flowDestination(g.view.ids[a], count);
      g.dest.push_back(std::uint16_t(d));
      g.arrived.push_back(g.crowd.hasArrived(g.view.pos[a], d) ? 1 : 0);
    }
    // Ghosts that have arrived left the crowd on their owner too: leave them out here.
    g.view.gatherGhosts(ghosts, [&](std::uint64_t id, crowd::Vec2 p) {
      return !g.crowd.hasArrived(p, flowDestination(id, count));
    });
    if (g.view.ids.empty()) {
      g.fallAsleepIn(store);
      continue;
    }
    // Far from every player an NPC steps less often (by the time it skipped), the farthest
    // along its field only; the plan depends on ids, positions and the tick alone.
    crowd::StepPlan plan;
    if (lod_) {
      // Crowded cells count walking agents and (walking) ghosts: the same on every rank.
      if (g.lod.settings().crowded_count > 0) {
        g.walking.resize(g.arrived.size());
        for (std::size_t a = 0; a < g.arrived.size(); ++a) g.walking[a] = !g.arrived[a];
        crowd::crowdingCounts(g.view.pos, g.walking, g.view.ghost_pos,
                              g.lod.settings().crowded_cell, g.crowding);
      }
      plan = g.lod.plan(g.view.ids, g.view.pos, players, tick, dt, {}, g.crowding);
    }
    arrived_before_.assign(g.arrived.begin(), g.arrived.end());
    g.crowd.step(g.view.agents(), g.dest, g.arrived, g.view.ghostSpan(), dt, plan);
    for (std::size_t a = 0; a < g.arrived.size(); ++a)
      if (g.arrived[a] && !arrived_before_[a]) arrived_now_.push_back(g.view.ids[a]);
    for (std::size_t a = 0; a < g.view.ids.size(); ++a)
      updates_ += (plan.empty() || plan.dt[a] > 0) && !g.arrived[a] ? 1 : 0;
    g.view.writeBack(store);
    std::size_t on_the_way = 0;
    for (std::uint8_t done : g.arrived) on_the_way += done ? 0 : 1;
    walking += on_the_way;
    if (on_the_way == 0) g.fallAsleepIn(store);
  }
  return walking;
}

}  // namespace zonesim::zone
