#include "zone_node/systems/flock_movement.h"

#include <algorithm>

#include "zone_node/cluster/ghost_store.h"
#include "zone_node/crowd/flock.h"
#include "zone_node/systems/flock_backend.h"
#include "zone_node/systems/planar_crowd.h"

namespace zonesim::zone {

/// One flocking population: its stepper and its ground-plane view.
struct FlockMovement::Group {
  Group(std::int32_t p, const crowd::FlockSettings& s, gpu::Backend b) : view(p), flock(s, b) {}
  PlanarCrowd view;
  FlockBackend flock;
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
    g.view.gatherAgents(store);
    g.view.gatherGhosts(ghosts);
    if (g.view.ids.empty()) continue;
    g.flock.step(g.view.agents(), g.view.ghostSpan(), dt);
    // The flock moves on the ground plane; the walls of the world stop it like any walker.
    g.view.writeBack(store, &scene_.world);
    stepped += g.view.index.size();
  }
  return stepped;
}

}  // namespace zonesim::zone
