#include "zone_node/systems/formation_movement.h"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>

#include "ai/navmesh.h"
#include "ai/navmesh_search.h"
#include "common/scene.h"
#include "common/scene_source.h"
#include "crowd/formation.h"
#include "crowd/lod.h"
#include "zone_node/formation_start.h"
#include "zone_node/ghost_store.h"
#include "zone_node/systems/crowd_lod.h"
#include "zone_node/systems/navmesh_obstacles.h"
#include "zone_node/systems/planar_crowd.h"
#include "zone_node/world_map.h"

namespace zonesim::zone {

namespace {

/// Counter of the id of the first NPC of population `p` (scene ids count up from 1).
std::uint64_t firstCounter(const Scene& scene, std::size_t p) {
  std::uint64_t before = 0;
  for (std::size_t q = 0; q < p; ++q) before += std::uint64_t(scene.npcs[q].count);
  return before + 1;
}

}  // namespace

/// One formation: its centre, the member stepper and the gather buffers.
struct FormationMovement::Group {
  Group(std::int32_t p, const WorldMap& map, const NpcFormation& f, const crowd::LodSettings& l)
      : view(p),
        formation(f),
        centre(formationSettings(f), {f.route[0].x, f.route[0].z}, formationHeading(f)),
        stepper(map.grid, map.frame, formationSettings(f)),
        lod(l) {}
  PlanarCrowd view;
  const NpcFormation& formation;
  std::uint64_t first = 0;  // id counter of member 0
  int count = 0;
  crowd::FormationCentre centre;
  std::uint64_t steps = 0;  // centre steps taken (ticks done)
  crowd::MemberStepper stepper;
  std::vector<crowd::MemberNeighbour> members;  // owned and ghosts, ascending id
  crowd::MemberState state;
  crowd::LevelOfDetail lod;

  int slotIndex(std::uint64_t id) const { return int(EntityId{id}.counter() - first); }
};

FormationMovement::FormationMovement(const Scene& scene, const WorldMap* map) : scene_(scene) {
  for (std::size_t p = 0; p < scene.npcs.size(); ++p) {
    const NpcFormation& f = scene.npcs[p].formation;
    if (!f.enabled) continue;
    if (!map) throw SceneError(sceneFile(scene) + ":0: map: a formation needs a map");
    auto g = std::make_unique<Group>(std::int32_t(p), *map, f, lodOf(scene.lod));
    g->first = firstCounter(scene, p);
    g->count = scene.npcs[p].count;
    // map.navigation: navmesh: the centre walks the funnelled mesh path, straight from corner
    // to corner, with map.agent_radius from walls and the static bodies closed as the agents'.
    std::unique_ptr<ai::NavMesh> mesh;
    std::unique_ptr<ai::NavMeshSearch> mesh_search;
    if (scene.map.navigation == ObstacleMap::kNavMesh) {
      mesh = std::make_unique<ai::NavMesh>(map->grid, navMeshBoxes(scene, map->frame),
                                           navMeshConfig(scene, map->frame));
      mesh_search = std::make_unique<ai::NavMeshSearch>(*mesh);
    }
    ai::GridSearch search(map->grid);
    auto plan = [&](std::span<const crowd::Vec2> points, std::vector<crowd::Vec2>& route) {
      return mesh_search ? crowd::planMeshRoute(*mesh_search, map->frame, points, route)
                         : crowd::planRoute(search, map->frame, points, route);
    };
    // Leg by leg, so that an unreachable point is named; each leg's first point is the last
    // leg's end.
    std::vector<crowd::Vec2> points, route, leg;
    for (std::size_t k = 0; k < f.route.size(); ++k) {
      const ScenePoint& at = f.route[k];
      std::string where = sceneFile(scene) + ":" + std::to_string(at.line) + ": populations[" +
                          std::to_string(p) + "].formation.route[" + std::to_string(k) + "]: ";
      if (!map->walkable(at.x, at.z)) throw SceneError(where + "lies on a blocked cell of the map");
      points.push_back({at.x, at.z});
      try {
        if (!plan(std::span<const crowd::Vec2>(points).last(k > 0 ? 2 : 1), leg))
          throw SceneError(where + "cannot be reached from the point before");
      } catch (const std::invalid_argument& e) {  // off the mesh
        throw SceneError(where + e.what());
      }
      route.insert(route.end(), leg.begin() + (k > 0 ? 1 : 0), leg.end());
    }
    g->centre.setRoute(std::move(route));
    groups_.push_back(std::move(g));
    reach_ = std::max(reach_, f.separation_radius);
  }
}

FormationMovement::~FormationMovement() = default;

FormationMovement::Group* FormationMovement::groupOf(std::int32_t population) const {
  for (const auto& g : groups_)
    if (g->view.population == population) return g.get();
  return nullptr;
}

const crowd::FormationCentre& FormationMovement::centre(std::size_t g) const {
  return groups_[g]->centre;
}

std::int32_t FormationMovement::population(std::size_t g) const {
  return groups_[g]->view.population;
}

crowd::Vec2 FormationMovement::slotPosition(const EntityStore& store, std::size_t i) const {
  Group* g = groupOf(store.npc[i].population);
  if (!g) return {store.pos[i].x(), store.pos[i].z()};
  return g->centre.slotPosition(
      formationSlot(g->formation, g->count, g->slotIndex(store.id[i].value)));
}

int FormationMovement::rejoinPlans() const {
  int n = 0;
  for (const auto& g : groups_) n += g->stepper.rejoinPlans();
  return n;
}

void FormationMovement::step(StepContext& ctx) {
  EntityStore& store = ctx.store;
  const GhostStore* ghosts = ctx.ghosts;
  const double dt = ctx.dt;
  const std::uint64_t tick = ctx.tick;
  updates_ = 0;
  for (const std::unique_ptr<Group>& gp : groups_) {
    Group& g = *gp;
    // Every rank takes the same centre steps from the scene's start: the same centre.
    for (; g.steps <= tick; ++g.steps) g.centre.advance(dt);
    g.view.gatherAgents(store);
    g.view.gatherGhosts(ghosts);
    // The members as they stood at the start of the step, in ascending id: the separation's
    // sums then run in one order whichever rank holds which member.
    g.members.clear();
    for (std::size_t a = 0; a < g.view.ids.size(); ++a)
      g.members.push_back({g.view.ids[a], g.view.pos[a]});
    for (std::size_t a = 0; a < g.view.ghost_ids.size(); ++a)
      g.members.push_back({g.view.ghost_ids[a], g.view.ghost_pos[a]});
    std::sort(g.members.begin(), g.members.end(),
              [](const crowd::MemberNeighbour& x, const crowd::MemberNeighbour& y) {
                return x.id < y.id;
              });
    // Far from every player a member steps less often (by the time it skipped), the farthest
    // toward its slot without pushing apart; the plan depends on ids, positions and the tick.
    crowd::StepPlan plan;
    if (scene_.lod.enabled) plan = g.lod.plan(g.view.ids, g.view.pos, ctx.players, tick, dt);
    for (std::size_t a = 0; a < g.view.ids.size(); ++a) {
      const double step_dt = plan.empty() ? dt : plan.dt[a];
      if (step_dt == 0.0) continue;
      const bool steer = plan.empty() || plan.steer[a];
      ++updates_;
      FormationMemberData& member = crowdState<FormationMemberData>(store.npc[g.view.index[a]]);
      crowd::MemberState& m = g.state;
      m.mode = crowd::MemberMode(member.mode);
      m.at = member.path_at;
      m.planned_for = {member.planned_x, member.planned_z};
      m.path.swap(member.path);
      const std::uint64_t id = g.view.ids[a];
      g.stepper.step(id, m, formationSlot(g.formation, g.count, g.slotIndex(id)), g.centre,
                     steer ? std::span<const crowd::MemberNeighbour>(g.members)
                           : std::span<const crowd::MemberNeighbour>(),
                     g.view.pos[a], g.view.vel[a], step_dt);
      member.mode = std::int32_t(m.mode);
      member.path_at = m.at;
      member.planned_x = m.planned_for.x;
      member.planned_z = m.planned_for.y;
      member.path.swap(m.path);
    }
    g.view.writeBack(store);
  }
}

}  // namespace zonesim::zone
