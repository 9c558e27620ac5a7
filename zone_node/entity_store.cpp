#include "zone_node/entity_store.h"

#include <atomic>
#include <cassert>

namespace zonesim::zone {

namespace {
// Membership stamps, unique across the stores of the process (0: an empty, untouched store).
std::uint64_t nextMembership() {
  static std::atomic<std::uint64_t> last{0};
  return last.fetch_add(1, std::memory_order_relaxed) + 1;
}
}  // namespace

std::size_t EntityStore::add(const EntityRecordData& r) {
  assert(!index_of_.count(r.id.value) && "entity added twice");
  std::size_t i = id.size();
  forEachEntityColumn([&](const auto& c) { (this->*c.store).push_back(r.*c.record); });
  dr.push_back({});
  index_of_[r.id.value] = i;
  if (r.kind == EntityKind::Avatar) avatar_of_player_[r.avatar.player_id] = i;
  ++kind_count_[std::size_t(r.kind)];
  membership_ = nextMembership();
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
  membership_ = nextMembership();
  index_of_.erase(id[i].value);
  if (kind[i] == EntityKind::Avatar) avatar_of_player_.erase(avatar[i].player_id);
  std::size_t last = size() - 1;
  if (i != last) {
    index_of_[id[last].value] = i;
    if (kind[last] == EntityKind::Avatar) avatar_of_player_[avatar[last].player_id] = i;
  }
  forEachEntityColumn([&](const auto& c) { swapPop(this->*c.store, i); });
  swapPop(dr, i);
}

EntityRecordData EntityStore::record(std::size_t i) const {
  EntityRecordData r;
  forEachEntityColumn([&](const auto& c) { r.*c.record = (this->*c.store)[i]; });
  return r;
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
