#pragma once
// The gateway's picture of the world: entity id -> latest state, the sim_time of that sample and
// the (cell, zone) it came from. Samples from different zones arrive in any order, so:
//  - a sample older than the one held for an entity is ignored;
//  - a leave removes an entity only if it still comes from the leaving (cell, zone) and nothing
//    newer arrived, and only after a grace period, so that a handoff (leave from zone A, enter
//    at zone B in the same tick, either first) never shows a client a despawn and a respawn;
//  - removed ids leave a short-lived tombstone so a late older sample cannot resurrect them.
// Times are on the gateway's timeline (epoch_timeline.h): a restored world's samples are newer
// than anything held from before its restart, and each records the jump it makes.

#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "dr/dr_model.h"
#include "dr/state_codec.h"
#include "zonesim.h"

namespace zonesim::gateway {

/// One entity as last heard of.
struct CachedEntity {
  zonesim_dds_EntityUpdate state{};
  double sim_time = 0;
  std::uint64_t tick = 0;  ///< zone tick the state was sampled at
  int cell = -1;
  int zone = -1;
  std::uint64_t version = 0;      ///< bumps on every accepted sample; clients are sent newer ones
  std::int64_t remove_at_ns = 0;  ///< 0 = live; else a leave is pending until this time
  std::uint32_t epoch = 0;        ///< cluster epoch of the sample held
};

/// A sample's time on the gateway's timeline, and its cluster epoch.
struct SampleAt {
  std::uint64_t tick = 0;
  double sim_time = 0;
  std::uint32_t epoch = 0;
};

/// Counts of what the cache did with samples.
struct CacheStats {
  std::uint64_t upserts = 0, stale = 0, invalid = 0, leaves = 0, ignored_leaves = 0, removals = 0;
};

class WorldCache {
 public:
  /// grace_ns: how long a leave waits for the matching enter before the entity is removed.
  explicit WorldCache(std::int64_t grace_ns);

  /// Applies one zone batch at `at`: enters and updates upsert, leaves start the grace.
  void applyBatch(const zonesim_dds_CellUpdateBatch& b, const SampleAt& at, std::int64_t now_ns);
  /// Applies a keyframe: its entities upsert; older entities of that (cell, zone) not in it leave.
  void applyKeyframe(const zonesim_dds_CellKeyframe& k, const SampleAt& at, std::int64_t now_ns);
  /// The same at the sample's own tick, sim time and epoch.
  void applyBatch(const zonesim_dds_CellUpdateBatch& b, std::int64_t now_ns) {
    applyBatch(b, {b.tick, b.sim_time, b.epoch}, now_ns);
  }
  void applyKeyframe(const zonesim_dds_CellKeyframe& k, std::int64_t now_ns) {
    applyKeyframe(k, {k.tick, k.sim_time, k.epoch}, now_ns);
  }
  /// Upserts one state unless older than what is held; false if ignored. A refresh (keyframe
  /// of an entity already held from the same source) updates the state without a new version:
  /// clients already following it keep to the zone's dead-reckoning updates.
  bool upsert(int cell, int zone, double sim_time, const zonesim_dds_EntityUpdate& e,
              bool refresh_only = false, std::uint64_t tick = 0, std::uint32_t epoch = 0);
  /// A leave of id from (cell, zone) at sim_time; false if it does not apply.
  bool leave(int cell, int zone, double sim_time, std::uint64_t id, std::int64_t now_ns);
  /// Removes entities whose grace expired and forgets old tombstones; returns how many removed.
  std::size_t sweep(std::int64_t now_ns);
  /// Forgets everything from a cell (its reader was deleted: nothing will update it).
  void dropCell(int cell);
  /// Removes every entity still held from an epoch before `epoch`: the restored world has had
  /// its time to say what it holds, and these are not in it. Returns how many.
  std::size_t retireEpochsBefore(std::uint32_t epoch, std::int64_t now_ns);
  /// How far each entity jumped when a newer epoch's sample replaced its state (its old state
  /// extrapolated to the new sample's time, to the new position), metres, in arrival order
  /// (the first kMaxJumps).
  const std::vector<float>& epochJumps() const { return epoch_jumps_m_; }
  static constexpr std::size_t kMaxJumps = 1 << 17;

  const CachedEntity* find(std::uint64_t id) const;
  std::size_t size() const { return entities_.size(); }
  /// The newest version handed out (versions are one counter over all entities, so an entity
  /// changed since a moment iff its version exceeds the counter's value then).
  std::uint64_t newestVersion() const { return version_counter_; }
  const CacheStats& stats() const { return stats_; }

  /// Visits (id, entity) for every entity held, in no particular order.
  template <typename F>
  void forEach(F&& f) const {
    for (const auto& [id, e] : entities_) f(id, e);
  }
  /// Visits (id, entity) for every entity whose source is the cell.
  template <typename F>
  void forEachInCell(int cell, F&& f) const {
    auto it = by_cell_.find(cell);
    if (it == by_cell_.end()) return;
    for (std::uint64_t id : it->second) f(id, entities_.at(id));
  }

 private:
  struct Tombstone {
    double sim_time;
    std::int64_t expires_ns;
  };
  void index(std::uint64_t id, int old_cell, int new_cell);
  void remove(std::uint64_t id, std::int64_t now_ns);

  std::int64_t grace_ns_;
  std::uint64_t version_counter_ = 0;
  std::unordered_map<std::uint64_t, CachedEntity> entities_;
  std::unordered_map<int, std::unordered_set<std::uint64_t>> by_cell_;
  std::unordered_map<std::uint64_t, Tombstone> tombstones_;
  std::unordered_map<std::uint64_t, std::int64_t> pending_;  // id -> remove_at_ns
  CacheStats stats_;
  std::vector<float> epoch_jumps_m_;
};

/// Where the entity's own dead-reckoning model puts it at sim time `at`.
dr::V3 predictedPosition(const CachedEntity& e, double at);
/// The cached state as the codec sends it: exactly the quantised state the zone sent.
dr::WireEntity wireEntity(const CachedEntity& e);
/// True if every field of a zone sample is finite and in range.
bool validSample(const zonesim_dds_EntityUpdate& e);

}  // namespace zonesim::gateway
