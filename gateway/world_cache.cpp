#include "gateway/world_cache.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "idl/dr_sample.h"
#include "wire/wire_verify.h"

namespace zonesim::gateway {

namespace {
// Long enough to outlive any reordering between zones' writers, short enough to stay small.
constexpr std::int64_t kTombstoneNs = 5'000'000'000;
// A sender heartbeats every few seconds; extrapolating further than this is guessing.
constexpr double kMaxExtrapolationSeconds = 10.0;

bool finite3(const zonesim_dds_Vec3f& v, float limit) {
  for (float c : {v.x, v.y, v.z})
    if (!std::isfinite(c) || std::fabs(c) > limit) return false;
  return true;
}
}  // namespace

bool validSample(const zonesim_dds_EntityUpdate& e) {
  const zonesim_dds_Quatf& q = e.rot;
  return e.id != 0 && e.kind <= kMaxEntityKind && finite3(e.pos, kMaxCoordinate) &&
         finite3(e.vel, kMaxSpeed) && finite3(e.acc, kMaxSpeed) && finite3(e.angvel, kMaxSpeed) &&
         std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w);
}

dr::V3 predictedPosition(const CachedEntity& e, double at) {
  double dt = std::clamp(at - e.sim_time, 0.0, kMaxExtrapolationSeconds);
  dr::WireEntity w = dds::toWireEntity(e.state, e.tick, e.cell);
  return dr::predictPosition(w.state, w.model.order, dt);
}

dr::WireEntity wireEntity(const CachedEntity& e) {
  return dds::toWireEntity(e.state, e.tick, e.cell);
}

WorldCache::WorldCache(std::int64_t grace_ns) : grace_ns_(grace_ns) {}

void WorldCache::index(std::uint64_t id, int old_cell, int new_cell) {
  if (old_cell == new_cell) return;
  if (old_cell >= 0) {
    auto it = by_cell_.find(old_cell);
    if (it != by_cell_.end()) {
      it->second.erase(id);
      if (it->second.empty()) by_cell_.erase(it);
    }
  }
  if (new_cell >= 0) by_cell_[new_cell].insert(id);
}

bool WorldCache::upsert(int cell, int zone, double sim_time, const zonesim_dds_EntityUpdate& e,
                        bool refresh_only, std::uint64_t tick, std::uint32_t epoch) {
  // Zones quarantine non-finite states; if one slips through it must not reach a client.
  if (!validSample(e)) {
    ++stats_.invalid;
    return false;
  }
  if (auto t = tombstones_.find(e.id); t != tombstones_.end() && sim_time < t->second.sim_time) {
    ++stats_.stale;
    return false;
  }
  auto [it, inserted] = entities_.try_emplace(e.id);
  CachedEntity& c = it->second;
  if (!inserted && sim_time < c.sim_time) {
    ++stats_.stale;
    return false;
  }
  int old_cell = inserted ? -1 : c.cell;
  bool new_epoch = !inserted && c.epoch < epoch;
  if (new_epoch && epoch_jumps_m_.size() < kMaxJumps) {
    dr::V3 was = predictedPosition(c, sim_time);
    double dx = was.x - e.pos.x, dy = was.y - e.pos.y, dz = was.z - e.pos.z;
    epoch_jumps_m_.push_back(float(std::sqrt(dx * dx + dy * dy + dz * dz)));
  }
  bool refresh = refresh_only && !inserted && !new_epoch && c.cell == cell && c.zone == zone &&
                 c.remove_at_ns == 0;
  c.state = e;
  c.sim_time = sim_time;
  c.tick = tick;
  c.cell = cell;
  c.zone = zone;
  c.epoch = epoch;
  if (!refresh) c.version = ++version_counter_;
  if (c.remove_at_ns != 0) pending_.erase(e.id);
  c.remove_at_ns = 0;
  index(e.id, old_cell, cell);
  tombstones_.erase(e.id);
  ++stats_.upserts;
  return true;
}

bool WorldCache::leave(int cell, int zone, double sim_time, std::uint64_t id, std::int64_t now_ns) {
  auto it = entities_.find(id);
  // A leave for a source that is no longer current, or older than the state held, means a
  // newer enter (another cell or zone) already arrived: the entity stays.
  if (it == entities_.end() || it->second.cell != cell || it->second.zone != zone ||
      sim_time < it->second.sim_time) {
    ++stats_.ignored_leaves;
    return false;
  }
  CachedEntity& c = it->second;
  c.sim_time = sim_time;
  if (c.remove_at_ns == 0) {
    c.remove_at_ns = now_ns + grace_ns_;
    pending_[id] = c.remove_at_ns;
  }
  ++stats_.leaves;
  return true;
}

void WorldCache::applyBatch(const zonesim_dds_CellUpdateBatch& b, const SampleAt& at,
                            std::int64_t now_ns) {
  for (std::uint32_t i = 0; i < b.enters._length; ++i)
    upsert(b.cell, b.zone, at.sim_time, b.enters._buffer[i], false, at.tick, at.epoch);
  for (std::uint32_t i = 0; i < b.updates._length; ++i)
    upsert(b.cell, b.zone, at.sim_time, b.updates._buffer[i], false, at.tick, at.epoch);
  for (std::uint32_t i = 0; i < b.leaves._length; ++i)
    leave(b.cell, b.zone, at.sim_time, b.leaves._buffer[i].id, now_ns);
}

void WorldCache::applyKeyframe(const zonesim_dds_CellKeyframe& k, const SampleAt& at,
                               std::int64_t now_ns) {
  std::unordered_set<std::uint64_t> present;
  present.reserve(k.entities._length);
  for (std::uint32_t i = 0; i < k.entities._length; ++i) {
    upsert(k.cell, k.zone, at.sim_time, k.entities._buffer[i], /*refresh_only=*/true, at.tick,
           at.epoch);
    present.insert(k.entities._buffer[i].id);
  }
  // The keyframe is the full state of (cell, zone): whatever we hold from there that is older
  // and absent has left, even if its leave sample never reached us.
  std::vector<std::uint64_t> gone;
  forEachInCell(k.cell, [&](std::uint64_t id, const CachedEntity& c) {
    if (c.zone == k.zone && c.sim_time < at.sim_time && !present.contains(id)) gone.push_back(id);
  });
  for (std::uint64_t id : gone) leave(k.cell, k.zone, at.sim_time, id, now_ns);
}

std::size_t WorldCache::retireEpochsBefore(std::uint32_t epoch, std::int64_t now_ns) {
  std::vector<std::uint64_t> old;
  for (const auto& [id, c] : entities_)
    if (c.epoch < epoch) old.push_back(id);
  for (std::uint64_t id : old) remove(id, now_ns);
  return old.size();
}

void WorldCache::remove(std::uint64_t id, std::int64_t now_ns) {
  auto it = entities_.find(id);
  if (it == entities_.end()) return;
  tombstones_[id] = Tombstone{it->second.sim_time, now_ns + kTombstoneNs};
  index(id, it->second.cell, -1);
  entities_.erase(it);
  pending_.erase(id);
  ++stats_.removals;
}

std::size_t WorldCache::sweep(std::int64_t now_ns) {
  std::vector<std::uint64_t> due;
  for (const auto& [id, at] : pending_)
    if (at <= now_ns) due.push_back(id);
  for (std::uint64_t id : due) remove(id, now_ns);
  std::erase_if(tombstones_, [&](const auto& kv) { return kv.second.expires_ns <= now_ns; });
  return due.size();
}

void WorldCache::dropCell(int cell) {
  auto it = by_cell_.find(cell);
  if (it == by_cell_.end()) return;
  std::vector<std::uint64_t> ids(it->second.begin(), it->second.end());
  for (std::uint64_t id : ids) {
    entities_.erase(id);
    pending_.erase(id);
  }
  by_cell_.erase(cell);
}

const CachedEntity* WorldCache::find(std::uint64_t id) const {
  auto it = entities_.find(id);
  return it == entities_.end() ? nullptr : &it->second;
}

}  // namespace zonesim::gateway
