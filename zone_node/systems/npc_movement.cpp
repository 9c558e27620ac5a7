#include "zone_node/systems/npc_movement.h"

#include "common/scene.h"
#include "zone_node/population.h"
#include "zone_node/systems/neighbourhood.h"
#include "zone_node/systems/steering.h"

namespace zonesim::zone {

namespace {

/// Planar push away from neighbours inside `radius`: radius/d - 1 for one at distance d, so 0 at
/// the radius, 1 at half of it and growing without bound toward contact; summed in id order.
Vec3 separation(const Vec3& p, const std::vector<Neighbour>& near, double radius) {
  Vec3 push = Vec3::Zero();
  for (const Neighbour& n : near) {
    Vec3 away = p - n.pos;
    away.y() = 0;
    double d = away.norm();
    if (d < 1e-9 || d >= radius) continue;
    push += away * ((radius / d - 1.0) / d);
  }
  return push;
}

Vec3 wanderVelocity(const Scene& scene, EntityStore& store, std::size_t i, double time) {
  NpcData& npc = store.npc[i];
  Vec3 to = npc.waypoint - store.pos[i];
  to.y() = 0;
  double dist = to.norm();
  // A gathering draws waypoints around its point while it lasts; its start and end retarget.
  bool gather = npc.gather_radius > 0 && time >= npc.gather_start && time < npc.gather_end;
  if (dist < npc.arrive_distance || gather != npc.gathering) {
    npc.gathering = gather;
    npc.waypoint = gather ? nextWaypoint(scene, npc.gather_point, npc.gather_radius,
                                         store.rng_state[i], store.id[i])
                          : nextWaypoint(scene, store.pos[i], npc.waypoint_radius,
                                         store.rng_state[i], store.id[i]);
    to = npc.waypoint - store.pos[i];
    to.y() = 0;
    dist = to.norm();
  }
  // Slow down inside the braking distance so NPCs arrive instead of orbiting the waypoint.
  double brake = npc.max_speed * npc.max_speed / (2.0 * npc.accel);
  double speed = dist < brake ? npc.max_speed * dist / brake : npc.max_speed;
  return dist > 1e-9 ? Vec3(to * (speed / dist)) : Vec3::Zero();
}

}  // namespace

WanderMovement::WanderMovement(const Scene& scene) : scene_(scene) {
  // Crowd populations' NPCs are skipped below: a scene of those alone has nothing to wander.
  for (const NpcPopulation& p : scene.npcs) active_ |= p.count > 0 && wanders(p);
}

void WanderMovement::step(StepContext& ctx) {
  const Scene& scene = scene_;
  EntityStore& store = ctx.store;
  const Neighbourhood& near = ctx.near;
  const double time = ctx.time, dt = ctx.dt;
  if (store.count(EntityKind::Npc) == 0) return;
  // Pass 1 reads positions only: every NPC decides from the tick's starting state.
  std::vector<std::pair<std::size_t, Vec3>> desired;
  desired.reserve(store.count(EntityKind::Npc));
  std::vector<Neighbour> found;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.kind[i] != EntityKind::Npc || store.npc[i].population >= 0)
      continue;                              // flock_movement
    if (store.agent[i].type >= 0) continue;  // agent_system
    Vec3 v = wanderVelocity(scene, store, i, time);
    const NpcData& npc = store.npc[i];
    if (npc.separation_radius > 0) {
      near.query(store.pos[i], npc.separation_radius, store.id[i], found);
      v += separation(store.pos[i], found, npc.separation_radius) *
           (npc.separation_weight * npc.max_speed);
      double speed = v.norm();
      if (speed > npc.max_speed) v *= npc.max_speed / speed;
    }
    desired.emplace_back(i, v);
  }
  for (const auto& [i, v] : desired) {
    steerAndIntegrate(store.pos[i], store.vel[i], v, store.npc[i].accel, dt);
    keepOnGround(scene.world, store.pos[i], store.vel[i]);
    store.rot[i] = facing(store.rot[i], store.vel[i]);
  }
}

}  // namespace zonesim::zone
