#include "zone_node/systems/avatar_movement.h"

#include "zone_node/systems/steering.h"

namespace zonesim::zone {

void stepAvatars(const SceneBox& world, EntityStore& store, double dt) {
  if (store.count(EntityKind::Avatar) == 0) return;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.kind[i] != EntityKind::Avatar) continue;
    const AvatarData& a = store.avatar[i];
    Vec3 desired(double(a.move_x) * a.max_speed, 0.0, double(a.move_z) * a.max_speed);
    steerAndIntegrate(store.pos[i], store.vel[i], desired, kAvatarAccel, dt);
    keepOnGround(world, store.pos[i], store.vel[i]);
    if (a.height > 0) holdHeight(world, a.height, store.pos[i], store.vel[i]);
    store.rot[i] = facing(store.rot[i], store.vel[i]);
  }
}

}  // namespace zonesim::zone
