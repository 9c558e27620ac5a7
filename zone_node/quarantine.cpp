#include "zone_node/quarantine.h"

namespace zonesim::zone {

namespace {
bool finite(const EntityStore& s, std::size_t i) {
  return s.pos[i].allFinite() && s.vel[i].allFinite() && s.rot[i].coeffs().allFinite();
}

static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Quat) == 4 * sizeof(double),
              "the store's columns are read as plain arrays of doubles");

// Whether n doubles are all finite: x - x is 0 for a finite x and NaN for an infinity or a NaN,
// and a NaN stays in a sum. Four sums, so the loop runs as vectors without reassociation.
bool allFinite(const double* x, std::size_t n) {
  double sum[4] = {0, 0, 0, 0};
  std::size_t k = 0;
  for (; k + 4 <= n; k += 4)
    for (std::size_t j = 0; j < 4; ++j) sum[j] += x[k + j] - x[k + j];
  for (; k < n; ++k) sum[0] += x[k] - x[k];
  return sum[0] + sum[1] + sum[2] + sum[3] == 0;
}

// Every row's position, velocity and orientation finite: one pass over each column, a few
// tenths of a nanosecond a row, so a zone whose movers are all finite (nearly every tick) pays
// no per-entity branch (issue 19's idle cost).
bool allFinite(const EntityStore& s) {
  if (s.size() == 0) return true;
  return allFinite(s.pos.data()->data(), 3 * s.size()) &&
         allFinite(s.vel.data()->data(), 3 * s.size()) &&
         allFinite(s.rot.data()->coeffs().data(), 4 * s.size());
}
}  // namespace

void Quarantine::begin(const EntityStore& store) {
  start_ = store.pos;
}

std::uint64_t Quarantine::apply(EntityStore& store) {
  // Held entities that left (destroyed, or migrated after the boundaries moved) are not ours.
  std::erase_if(frozen_, [&](const auto& f) { return !store.indexOf(EntityId{f.first}); });
  if (frozen_.empty() && allFinite(store)) return 0;
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
