#pragma once
// Read-only copies of other ranks' entities near this zone (LAMMPS' ghost atoms). Systems read
// them as neighbours; only the owner ever writes an entity's state. Refreshed every tick by the
// halo exchange; the arrays are rebuilt whole, so indices mean nothing across ticks.

#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "common/entity_id.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

/// A velocity change this zone's contacts gave another zone's entity: sent back to its owner
/// (LAMMPS' reverse_comm), which alone writes the entity's state.
struct GhostImpulse {
  EntityId id;
  int owner = -1;
  Vec3 dv = Vec3::Zero();  ///< linear, m/s
  Vec3 dw = Vec3::Zero();  ///< angular, rad/s
};

class GhostStore {
 public:
  std::size_t size() const { return id.size(); }
  void clear();
  /// Appends a ghost owned by rank `owner`; `flock`: an NPC's flock population (-1: none);
  /// `agent`: an NPC's AI agent type (-1: not an agent).
  void add(EntityId e, EntityKind k, const Vec3& p, const Vec3& v, const Quat& q, const BodyData& b,
           int owner, std::int32_t flock = -1, std::int32_t agent = -1);
  std::optional<std::size_t> indexOf(EntityId e) const;

  std::vector<EntityId> id;
  std::vector<EntityKind> kind;
  std::vector<Vec3> pos;
  std::vector<Vec3> vel;
  std::vector<Quat> rot;
  std::vector<BodyData> body;  ///< shape and material, for rigid-body ghosts
  std::vector<int> owner;
  std::vector<std::int32_t> flock;  ///< NPCs: population index when flocking, else -1
  std::vector<std::int32_t> agent;  ///< NPCs: AI agent type, else -1 (agents tell foe from kin)

 private:
  std::unordered_map<std::uint64_t, std::size_t> index_of_;
};

}  // namespace zonesim::zone
