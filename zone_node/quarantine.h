#pragma once
// World::quarantineNonFinite's rule for the zone's other movers (walkers, crowds, agents,
// avatars): an entity whose state became non-finite is frozen where it last was finite, with no
// velocity, and stays frozen, so a non-finite state never reaches a neighbour, a ghost, a
// migration or a subscriber. Rigid bodies are left to physics/, which applies the same rule.

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "common/math.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

class Quarantine {
 public:
  /// Remembers where each entity starts the phase; call before the systems move them.
  void begin(const EntityStore& store);
  /// Freezes the entities that are non-finite now and holds those frozen before; returns how
  /// many were frozen for the first time.
  std::uint64_t apply(EntityStore& store);
  /// Entities of this zone held frozen.
  std::size_t frozen() const { return frozen_.size(); }
  /// Whether entity `id` is held frozen.
  bool holds(EntityId id) const { return frozen_.contains(id.value); }

 private:
  std::vector<Vec3> start_;                         // by index, as begin() found the store
  std::unordered_map<std::uint64_t, Vec3> frozen_;  // id -> where it is held
};

}  // namespace zonesim::zone
