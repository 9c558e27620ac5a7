#pragma once
// The ground-plane view of one crowd population, shared by the zone's crowd systems (flocks,
// flow fields): its NPCs and same-population ghosts copied from the stores into the plain
// arrays the crowd library steps (x, z of the zone become x, y of the plane), and the result
// written back. The buffers are kept between ticks so a step allocates nothing once grown.

#include <cstdint>
#include <vector>

#include "common/scene_geometry.h"
#include "crowd/agents.h"
#include "zone_node/entity_store.h"
#include "zone_node/ghost_store.h"

namespace zonesim::zone {

/// One population's agents and ghosts on the ground plane, gathered each tick.
struct PlanarCrowd {
  /// An empty view of population `p` (the NPCs whose `npc.population` is `p`).
  explicit PlanarCrowd(std::int32_t p) : population(p) {}

  /// Copies this population's NPCs from `store` (store order), replacing the last gather.
  void gatherAgents(const EntityStore& store);
  /// Copies this population's ghosts for which `keep(id, pos)` holds, replacing the last ones.
  template <class Keep>
  void gatherGhosts(const GhostStore* ghosts, Keep keep);
  /// Copies all of this population's ghosts.
  void gatherGhosts(const GhostStore* ghosts) {
    gatherGhosts(ghosts, [](std::uint64_t, crowd::Vec2) { return true; });
  }
  /// Writes the stepped positions and velocities back to `store`, on the ground, each NPC
  /// turned to face its motion; with `walls`, the world's walls stop it like any walker.
  void writeBack(EntityStore& store, const SceneBox* walls = nullptr) const;

  /// The gathered agents, for the crowd library's steps.
  crowd::AgentSpan agents() { return {ids, pos, vel}; }
  /// The gathered ghosts, for the crowd library's steps.
  crowd::GhostSpan ghostSpan() const { return {ghost_ids, ghost_pos, ghost_vel}; }

  std::int32_t population;                        ///< population index in the scene
  std::vector<std::size_t> index;                 ///< store index of each gathered agent
  std::vector<std::uint64_t> ids;                 ///< agent ids, gather order
  std::vector<crowd::Vec2> pos, vel;              ///< agent state on the plane
  std::vector<std::uint64_t> ghost_ids;           ///< ghost ids
  std::vector<crowd::Vec2> ghost_pos, ghost_vel;  ///< ghost state on the plane
};

template <class Keep>
void PlanarCrowd::gatherGhosts(const GhostStore* ghosts, Keep keep) {
  ghost_ids.clear();
  ghost_pos.clear();
  ghost_vel.clear();
  if (!ghosts) return;
  // Without the column no crowd registered it: no ghost is of this population.
  const std::optional<std::size_t> column = ghosts->columnIndex(kCrowdPopulation);
  if (!column) return;
  for (std::size_t k = 0; k < ghosts->size(); ++k) {
    if (ghosts->kind[k] != EntityKind::Npc || ghosts->value(*column, k) != population) continue;
    crowd::Vec2 p{ghosts->pos[k].x(), ghosts->pos[k].z()};
    if (!keep(ghosts->id[k].value, p)) continue;
    ghost_ids.push_back(ghosts->id[k].value);
    ghost_pos.push_back(p);
    ghost_vel.push_back({ghosts->vel[k].x(), ghosts->vel[k].z()});
  }
}

}  // namespace zonesim::zone
