#include "zone_node/systems/flock_movement.h"

#include <algorithm>

#include "common/scene.h"
#include "crowd/flock.h"
#include "zone_node/ghost_store.h"
#include "zone_node/systems/crowd_lod.h"
#include "zone_node/systems/flock_backend.h"
#include "zone_node/systems/planar_crowd.h"

namespace zonesim::zone {

/// One flocking population: its stepper and its ground-plane view.
struct FlockMovement::Group {
  Group(std::int32_t p, const crowd::FlockSettings& s, gpu::Backend b, const crowd::LodSettings& l)
      : view(p), flock(s, b), lod(l) {}
  PlanarCrowd view;
  FlockBackend flock;
  crowd::LevelOfDetail lod;
  bool hasGoal = false;
  crowd::Vec2 goal;                   // the point the flock heads for
  double goalSpeed = 0;               // m/s toward it
  double goalSlowRadius = 1;          // m: speed ramps down to 0 this close
  std::vector<crowd::Vec2> goal_vel;  // per gathered NPC, kept warm
  std::vector<std::uint32_t> crowding;  // per NPC: its cell's count (empty: not used)
};

namespace {

crowd::FlockSettings settingsOf(const NpcFlock& f, double halo_width) {
  crowd::FlockSettings s;
  s.neighbour_radius = f.radius;
  s.separation_radius = f.separation_radius;
  s.separation_weight = f.separation_weight;
  s.alignment_weight = f.alignment_weight;
  s.cohesion_weight = f.cohesion_weight;
  s.max_speed = f.max_speed;
  s.max_force = f.max_force;
  s.goal_weight = f.goal_weight;
  s.body_radius = f.body_radius;
  s.sight = halo_width;  // every neighbour that could bind a body is a ghost on every rank
  return s;
}

}  // namespace

FlockMovement::FlockMovement(const Scene& scene, const std::string& gpu_mode,
                             const gpu::OffloadThresholds& thresholds, int ranks)
    : scene_(scene), lod_(scene.lod.enabled) {
  for (std::size_t p = 0; p < scene.npcs.size(); ++p) {
    const NpcFlock& f = scene.npcs[p].flock;
    if (!f.enabled) continue;
    const std::size_t share = std::size_t(scene.npcs[p].count) / std::size_t(std::max(1, ranks));
    // The device kernel has no bodies: a flock that keeps them apart runs on the CPU.
    gpu::Backend b =
        f.body_radius > 0 ? gpu::Backend::Cpu : flockBackendFor(gpu_mode, share, thresholds);
    auto g = std::make_unique<Group>(std::int32_t(p), settingsOf(f, scene.halo_width), b,
                                     lodOf(scene.lod));
    g->hasGoal = f.has_goal;
    g->goal = {f.goal_x, f.goal_z};
    g->goalSpeed = f.goal_speed > 0 ? f.goal_speed : f.max_speed;
    g->goalSlowRadius = f.goal_slow_radius;
    groups_.push_back(std::move(g));
    if (backend_ != "opencl") backend_ = gpu::backendName(b);
    reach_ = std::max(reach_, f.radius);
  }
}

FlockMovement::~FlockMovement() = default;

void FlockMovement::step(StepContext& ctx) {
  advance(ctx.store, ctx.ghosts, ctx.dt, ctx.players, std::int64_t(ctx.tick));
}

std::size_t FlockMovement::advance(EntityStore& store, const GhostStore* ghosts, double dt,
                                   std::span<const crowd::Vec2> players, std::int64_t tick) {
  std::size_t stepped = 0;
  updates_ = 0;
  for (const std::unique_ptr<Group>& gp : groups_) {
    Group& g = *gp;
    g.view.gatherAgents(store);
    g.view.gatherGhosts(ghosts);
    if (g.view.ids.empty()) continue;
    // The goal velocity depends on the NPC's position alone, so every rank computes the same.
    std::span<const crowd::Vec2> goal_vel;
    if (g.hasGoal) {
      g.goal_vel.resize(g.view.pos.size());
      for (std::size_t a = 0; a < g.view.pos.size(); ++a) {
        crowd::Vec2 to = g.goal - g.view.pos[a];
        double speed = g.goalSpeed * std::min(1.0, crowd::length(to) / g.goalSlowRadius);
        g.goal_vel[a] = crowd::withLength(to, speed);
      }
      goal_vel = g.goal_vel;
    }
    // Far from every player a flocker steps less often (by the time it skipped), the farthest
    // on its goal velocity only; the plan depends on ids, positions and the tick alone.
    crowd::StepPlan plan;
    if (lod_) {
      if (g.lod.settings().crowded_count > 0) {
        crowd::crowdingCounts(g.view.pos, {}, g.view.ghost_pos, g.lod.settings().crowded_cell,
                              g.crowding);
      }
      plan = g.lod.plan(g.view.ids, g.view.pos, players, tick, dt, {}, g.crowding);
    }
    g.flock.step(g.view.agents(), g.view.ghostSpan(), dt, goal_vel, plan);
    updates_ += lod_ ? g.lod.updated() : g.view.ids.size();
    // The flock moves on the ground plane; the walls of the world stop it like any walker.
    g.view.writeBack(store, &scene_.world);
    stepped += g.view.index.size();
  }
  return stepped;
}

}  // namespace zonesim::zone
