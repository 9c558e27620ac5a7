#include "zone_node/systems/planar_crowd.h"

#include "zone_node/systems/steering.h"

namespace zonesim::zone {

void PlanarCrowd::gatherAgents(const EntityStore& store) {
  index.clear();
  ids.clear();
  pos.clear();
  vel.clear();
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.kind[i] != EntityKind::Npc || store.npc[i].population != population) continue;
    index.push_back(i);
    ids.push_back(store.id[i].value);
    pos.push_back({store.pos[i].x(), store.pos[i].z()});
    vel.push_back({store.vel[i].x(), store.vel[i].z()});
  }
}

void PlanarCrowd::writeBack(EntityStore& store, const SceneBox* walls) const {
  for (std::size_t a = 0; a < index.size(); ++a) {
    std::size_t i = index[a];
    store.pos[i] = Vec3(pos[a].x, store.pos[i].y(), pos[a].y);
    store.vel[i] = Vec3(vel[a].x, 0.0, vel[a].y);
    if (walls) keepOnGround(*walls, store.pos[i], store.vel[i]);
    store.rot[i] = facing(store.rot[i], store.vel[i]);
  }
}

}  // namespace zonesim::zone
