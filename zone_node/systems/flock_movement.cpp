#include "zone_node/systems/flock_movement.h"

#include <algorithm>

#include "zone_node/cluster/ghost_store.h"
#include "zone_node/crowd/flock.h"
#include "zone_node/systems/flock_backend.h"
#include "zone_node/systems/steering.h"

namespace zonesim::zone {

/// One flocking population: its stepper and the gather buffers (kept to avoid reallocation).
struct FlockMovement::Group {
  Group(std::int32_t p, const crowd::FlockSettings& s, gpu::Backend b)
      : population(p), flock(s, b) {}
  std::int32_t population;
  FlockBackend flock;
  std::vector<std::size_t> index;  // store index of each gathered agent
  std::vector<std::uint64_t> ids, ghost_ids;
  std::vector<crowd::Vec2> pos, vel, ghost_pos, ghost_vel;
};

namespace {

crowd::FlockSettings settingsOf(const NpcFlock& f) {
  crowd::FlockSettings s;
  s.neighbourRadius = f.radius;
  s.separationRadius = f.separation_radius;
  s.separationWeight = f.separation_weight;
  s.alignmentWeight = f.alignment_weight;
  s.cohesionWeight = f.cohesion_weight;
  s.maxSpeed = f.max_speed;
  s.maxForce = f.max_force;
  return s;
}

}  // namespace

FlockMovement::FlockMovement(const Scene& scene, const std::string& gpu_mode,
                             const gpu::OffloadThresholds& thresholds, int ranks)
    : scene_(scene) {
  for (std::size_t p = 0; p < scene.npcs.size(); ++p) {
    const NpcFlock& f = scene.npcs[p].flock;
    if (!f.enabled) continue;
    const std::size_t share = std::size_t(scene.npcs[p].count) / std::size_t(std::max(1, ranks));
    gpu::Backend b = flockBackendFor(gpu_mode, share, thresholds);
    groups_.push_back(std::make_unique<Group>(std::int32_t(p), settingsOf(f), b));
    if (backend_ != "opencl") backend_ = gpu::backendName(b);
    reach_ = std::max(reach_, f.radius);
  }
}

FlockMovement::~FlockMovement() = default;

std::size_t FlockMovement::step(EntityStore& store, const GhostStore* ghosts, double dt) {
  std::size_t stepped = 0;
  for (const std::unique_ptr<Group>& gp : groups_) {
    Group& g = *gp;
    g.index.clear();
    g.ids.clear();
    g.pos.clear();
    g.vel.clear();
    for (std::size_t i = 0; i < store.size(); ++i) {
      if (store.kind[i] != EntityKind::Npc || store.npc[i].flock != g.population) continue;
      g.index.push_back(i);
      g.ids.push_back(store.id[i].value);
      g.pos.push_back({store.pos[i].x(), store.pos[i].z()});
      g.vel.push_back({store.vel[i].x(), store.vel[i].z()});
    }
    g.ghost_ids.clear();
    g.ghost_pos.clear();
    g.ghost_vel.clear();
    if (ghosts) {
      for (std::size_t k = 0; k < ghosts->size(); ++k) {
        if (ghosts->kind[k] != EntityKind::Npc || ghosts->flock[k] != g.population) continue;
        g.ghost_ids.push_back(ghosts->id[k].value);
        g.ghost_pos.push_back({ghosts->pos[k].x(), ghosts->pos[k].z()});
        g.ghost_vel.push_back({ghosts->vel[k].x(), ghosts->vel[k].z()});
      }
    }
    if (g.ids.empty()) continue;
    g.flock.step(crowd::AgentSpan{g.ids, g.pos, g.vel},
                 crowd::GhostSpan{g.ghost_ids, g.ghost_pos, g.ghost_vel}, dt);
    for (std::size_t a = 0; a < g.index.size(); ++a) {
      std::size_t i = g.index[a];
      // The flock moves on the ground plane; the walls of the world stop it like any walker.
      store.pos[i] = Vec3(g.pos[a].x, store.pos[i].y(), g.pos[a].y);
      store.vel[i] = Vec3(g.vel[a].x, 0.0, g.vel[a].y);
      keepOnGround(scene_.world, store.pos[i], store.vel[i]);
      store.rot[i] = facing(store.rot[i], store.vel[i]);
    }
    stepped += g.index.size();
  }
  return stepped;
}

}  // namespace zonesim::zone
