#include "zone_node/ghost_store.h"

namespace zonesim::zone {

void GhostStore::clear() {
  id.clear();
  kind.clear();
  pos.clear();
  vel.clear();
  rot.clear();
  body.clear();
  owner.clear();
  flock.clear();
  agent.clear();
  index_of_.clear();
}

void GhostStore::add(EntityId e, EntityKind k, const Vec3& p, const Vec3& v, const Quat& q,
                     const BodyData& b, int from, std::int32_t group, std::int32_t agent_type) {
  index_of_[e.value] = id.size();
  id.push_back(e);
  kind.push_back(k);
  pos.push_back(p);
  vel.push_back(v);
  rot.push_back(q);
  body.push_back(b);
  owner.push_back(from);
  flock.push_back(group);
  agent.push_back(agent_type);
}

std::optional<std::size_t> GhostStore::indexOf(EntityId e) const {
  auto it = index_of_.find(e.value);
  if (it == index_of_.end()) return std::nullopt;
  return it->second;
}

}  // namespace zonesim::zone
