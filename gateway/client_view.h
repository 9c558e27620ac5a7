#pragma once
// What one client has been sent, and the per-tick diff against what it should see now:
// entities new to it (Spawn, full state), gone from it (Despawn), and known ones that got a
// fresher sample since last sent (StateBatch).

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "common/flat_id_map.h"
#include "common/interest_grid.h"

namespace zonesim::gateway {

class WorldCache;
class WorldSnapshot;

/// An entity the client should see now, with the cache version of its state.
struct VisibleEntity {
  std::uint64_t id = 0;
  std::uint64_t version = 0;
};

/// The result of one diff; each list is in ascending id order.
struct ViewDiff {
  std::vector<std::uint64_t> spawns, despawns, updates;
  bool empty() const { return spawns.empty() && despawns.empty() && updates.empty(); }
  /// Empties the lists, keeping their storage.
  void clear() {
    spawns.clear();
    despawns.clear();
    updates.clear();
  }
};

/// Entity id -> version last sent to one client.
class ClientView {
 public:
  /// Diffs visible (any order, no duplicates) against what was sent and records the new state.
  ViewDiff diff(const std::vector<VisibleEntity>& visible);
  /// The same into `d` (cleared first), reusing its storage.
  void diff(const std::vector<VisibleEntity>& visible, ViewDiff& d);
  /// Between full scans: lists as updates the entities of `changed` that the client holds and
  /// was sent an older version of; no spawns, no despawns (into `d`, cleared first).
  void diffKnown(const std::vector<VisibleEntity>& changed, ViewDiff& d);
  bool knows(std::uint64_t id) const { return known_.contains(id); }
  /// An update held back: the next diff lists the entity's state again (versions start at 1).
  void defer(std::uint64_t id) {
    if (Sent* s = known_.find(id)) s->version = 0;
  }
  /// A spawn held back: the next diff lists the entity as a spawn again.
  void forget(std::uint64_t id) { known_.erase(id); }
  /// A despawn held back: the client still holds the entity, so the next diff lists it as a
  /// despawn again, or as an update if it is visible again by then (epoch 0 is never current:
  /// diff counts from 1; version 0 is older than any state).
  void holdDespawn(std::uint64_t id) { known_.insertOrAssign(id, Sent{0, 0}); }
  std::size_t size() const { return known_.size(); }
  /// Calls f(id) for every entity the client holds, in no particular order.
  template <typename F>
  void forEachKnown(F&& f) const {
    known_.forEach([&](std::uint64_t id, const Sent&) { f(id); });
  }

 private:
  struct Sent {
    std::uint64_t version;
    std::uint64_t epoch;  // diff() call that last saw it visible
  };
  FlatIdMap<Sent> known_;
  std::uint64_t epoch_ = 0;
};

/// Auras by entity kind (0 NPC, 1 avatar, 2 rigid body, 3 emitter, 4 item), metres.
using Auras = std::array<double, 5>;

/// The seed's rule: A sees B when A is inside B's aura and B inside A's nimbus, i.e. when
/// their distance is within both. Takes the squared distance (no square root per pair).
inline bool auraNimbusAllows(double distance_sq, double aura_of_b, double nimbus_of_a) {
  double r = std::min(aura_of_b, nimbus_of_a);
  return distance_sq <= r * r;
}

/// A player's nimbus: the base grown by speed * per_speed, capped (a runner or a flyer sees
/// farther than a walker), never below the base.
inline double grownNimbus(double base, double speed, double per_speed, double max_nimbus) {
  return std::max(base, std::min(max_nimbus, base + speed * per_speed));
}

/// Where a player looks from, and how far.
struct ViewPoint {
  double x = 0, z = 0;
  double nimbus = 60;  ///< entities within this planar distance are shown
  double keep = 66;    ///< entities already shown stay until beyond this (no edge flicker)
  /// Per-kind auras; an entity is shown within min(aura, nimbus), kept within
  /// min(aura, nimbus) * keep / nimbus. Default: no aura limit.
  Auras aura{1e30, 1e30, 1e30, 1e30, 1e30};
  std::uint64_t self = 0;  ///< the player's avatar: always visible once known
  std::uint64_t self_version = 0;  ///< its cache version (0: not cached yet)
  double sim_now = 0;      ///< positions are extrapolated to this time before measuring
};

/// The entities a player should see: within nimbus (or keep, if already known) of the point,
/// at the snapshot's time (a gateway builds one snapshot a tick for all its players). Appends
/// to `out` (cleared first), so a caller that keeps it allocates nothing once warm.
void selectVisible(const WorldSnapshot& snapshot, const InterestGrid& grid, const ViewPoint& at,
                   const ClientView& known, std::vector<VisibleEntity>& out);
/// Between full scans: the entities that changed since the snapshot before and that the
/// player holds, from the cells that meet its disc (the avatar wherever it is). Appends to
/// `out` (cleared first).
void selectChanged(const WorldSnapshot& snapshot, const InterestGrid& grid, const ViewPoint& at,
                   const ClientView& known, std::vector<VisibleEntity>& out);
/// The same from the cache at at.sim_now, for one-off callers (a snapshot built for one view).
std::vector<VisibleEntity> selectVisible(const WorldCache& cache, const InterestGrid& grid,
                                         const ViewPoint& at, const ClientView& known);

}  // namespace zonesim::gateway
