#include "zone_node/quarantine.h"

namespace zonesim::zone {

namespace {
bool finite(const EntityStore& s, std::size_t i) {
  return s.pos[i].allFinite() && s.vel[i].allFinite() && s.rot[i].coeffs().allFinite();
}
}  // namespace

void Quarantine::begin(const EntityStore& store) {
  start_ = store.pos;
}

std::uint64_t Quarantine::apply(EntityStore& store) {
  // Held entities that left (destroyed, or migrated after the boundaries moved) are not ours.
  std::erase_if(frozen_, [&](const auto& f) { return !store.indexOf(EntityId{f.first}); });
  std::uint64_t newly = 0;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.kind[i] == EntityKind::RigidBody) continue;
    auto held = frozen_.find(store.id[i].value);
    if (held == frozen_.end()) {
      if (finite(store, i)) continue;
      // Where the phase found it, or the origin if it came in non-finite.
      Vec3 at = i < start_.size() && start_[i].allFinite() ? start_[i] : Vec3::Zero();
      held = frozen_.emplace(store.id[i].value, at).first;
      ++newly;
    }
    // Its systems may move it again (their inputs may be what is non-finite): hold it.
    store.pos[i] = held->second;
    store.vel[i].setZero();
    if (!store.rot[i].coeffs().allFinite()) store.rot[i] = Quat::Identity();
    if (store.kind[i] == EntityKind::Avatar) store.avatar[i].move_x = store.avatar[i].move_z = 0;
  }
  return newly;
}

}  // namespace zonesim::zone
