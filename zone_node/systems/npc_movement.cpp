#include "zone_node/systems/npc_movement.h"

#include "zone_node/population.h"
#include "zone_node/systems/steering.h"

namespace zonesim::zone {

void stepNpcs(const Scene& scene, EntityStore& store, double dt) {
  if (store.count(EntityKind::Npc) == 0) return;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.kind[i] != EntityKind::Npc) continue;
    NpcData& npc = store.npc[i];
    Vec3 to = npc.waypoint - store.pos[i];
    to.y() = 0;
    double dist = to.norm();
    if (dist < npc.arrive_distance) {
      npc.waypoint =
          nextWaypoint(scene, store.pos[i], npc.waypoint_radius, store.rng_state[i], store.id[i]);
      to = npc.waypoint - store.pos[i];
      to.y() = 0;
      dist = to.norm();
    }
    // Slow down inside the braking distance so NPCs arrive instead of orbiting the waypoint.
    double brake = npc.max_speed * npc.max_speed / (2.0 * npc.accel);
    double speed = dist < brake ? npc.max_speed * dist / brake : npc.max_speed;
    Vec3 desired = dist > 1e-9 ? Vec3(to * (speed / dist)) : Vec3::Zero();
    steerAndIntegrate(store.pos[i], store.vel[i], desired, npc.accel, dt);
    keepOnGround(scene.world, store.pos[i], store.vel[i]);
    store.rot[i] = facing(store.rot[i], store.vel[i]);
  }
}

}  // namespace zonesim::zone
