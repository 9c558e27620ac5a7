#include "zone_node/entity_store.h"

#include <cassert>

namespace zonesim::zone {

std::size_t EntityStore::add(const EntityRecordData& r) {
  assert(!index_of_.count(r.id.value) && "entity added twice");
  std::size_t i = id.size();
  id.push_back(r.id);
  kind.push_back(r.kind);
  pos.push_back(r.pos);
  vel.push_back(r.vel);
  rot.push_back(r.rot);
  rng_state.push_back(r.rng_state);
  npc.push_back(r.npc);
  avatar.push_back(r.avatar);
  body.push_back(r.body);
  emitter.push_back(r.emitter);
  agent.push_back(r.agent);
  dr.push_back({});
  index_of_[r.id.value] = i;
  if (r.kind == EntityKind::Avatar) avatar_of_player_[r.avatar.player_id] = i;
  ++kind_count_[std::size_t(r.kind)];
  return i;
}

namespace {
template <typename T>
void swapPop(std::vector<T>& v, std::size_t i) {
  if (i + 1 != v.size()) v[i] = std::move(v.back());
  v.pop_back();
}
}  // namespace

void EntityStore::removeAt(std::size_t i) {
  assert(i < size());
  --kind_count_[std::size_t(kind[i])];
  index_of_.erase(id[i].value);
  if (kind[i] == EntityKind::Avatar) avatar_of_player_.erase(avatar[i].player_id);
  std::size_t last = size() - 1;
  if (i != last) {
    index_of_[id[last].value] = i;
    if (kind[last] == EntityKind::Avatar) avatar_of_player_[avatar[last].player_id] = i;
  }
  swapPop(id, i);
  swapPop(kind, i);
  swapPop(pos, i);
  swapPop(vel, i);
  swapPop(rot, i);
  swapPop(rng_state, i);
  swapPop(npc, i);
  swapPop(avatar, i);
  swapPop(body, i);
  swapPop(emitter, i);
  swapPop(agent, i);
  swapPop(dr, i);
}

EntityRecordData EntityStore::record(std::size_t i) const {
  return {id[i],  kind[i],   pos[i],  vel[i],     rot[i],  rng_state[i],
          npc[i], avatar[i], body[i], emitter[i], agent[i]};
}

std::optional<std::size_t> EntityStore::indexOf(EntityId e) const {
  auto it = index_of_.find(e.value);
  if (it == index_of_.end()) return std::nullopt;
  return it->second;
}

std::optional<std::size_t> EntityStore::avatarOf(std::uint64_t player_id) const {
  auto it = avatar_of_player_.find(player_id);
  if (it == avatar_of_player_.end()) return std::nullopt;
  return it->second;
}

}  // namespace zonesim::zone
