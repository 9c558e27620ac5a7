#include "zone_node/avatar_spawn.h"

#include <algorithm>

#include "common/scene.h"

namespace zonesim::zone {

std::optional<EntityRecordData> newAvatar(const Scene& scene, std::uint64_t player_id, double x,
                                          double z, std::uint8_t kind) {
  std::optional<PlayerKind> k = playerKind(scene.clients, kind);
  if (!k) return std::nullopt;
  // Inside the world, short of its far edges.
  x = std::clamp(x, scene.world.min.x, scene.world.max.x - 1e-6);
  z = std::clamp(z, scene.world.min.z, scene.world.max.z - 1e-6);
  EntityRecordData r;
  r.kind = EntityKind::Avatar;
  r.pos = Vec3(x, scene.world.min.y + k->height, z);
  r.avatar.player_id = player_id;
  r.avatar.max_speed = k->speed;
  r.avatar.kind = kind;
  r.avatar.height = k->height;
  // A player arrives with the items the scene's interactions give (nothing to give without).
  if (scene.interactions.enabled) r.combat.items = scene.interactions.items_per_avatar;
  return r;
}

}  // namespace zonesim::zone
