#pragma once
// Read-only copies of other ranks' entities near this zone (LAMMPS' ghost atoms). Systems read
// them as neighbours; only the owner ever writes an entity's state. Refreshed every tick by the
// halo exchange; the arrays are rebuilt whole, so indices mean nothing across ticks.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "common/entity_id.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

/// A per-entity value that a system reads on ghosts too (an NPC's crowd population, an agent's
/// type). Systems name the columns they need (ZoneSystem::ghostColumns); the halo sends one
/// integer per registered column with every ghost, so it carries no fixed slot per system.
struct GhostColumn {
  std::string name;
  /// The owner's values for every entity of its store, by index (one call per column and
  /// refresh, not one per entity: the halo packs thousands of ghosts a tick).
  std::function<void(const EntityStore&, std::vector<std::int64_t>&)> read;
};

/// The crowd population an NPC's crowd system moves it for (NpcData::population; -1: none), so
/// flocks, flow crowds and formations see only their kin across a border.
GhostColumn crowdPopulationColumn();
inline constexpr const char* kCrowdPopulation = "crowd.population";
/// An NPC's AI agent type (-1: not an agent), so agents tell foe from kin across a border.
GhostColumn agentTypeColumn();
inline constexpr const char* kAgentType = "agent.type";

class GhostStore {
 public:
  std::size_t size() const { return id.size(); }
  void clear();
  /// Registers a column (once per name; a second registration of a name returns the first's
  /// index). Only while the store holds no ghosts.
  std::size_t addColumn(GhostColumn column);
  /// The registered columns, in registration order.
  const std::vector<GhostColumn>& columns() const { return columns_; }
  /// Index of the column registered as `name`, if any.
  std::optional<std::size_t> columnIndex(std::string_view name) const;
  /// Ghost g's value of column c.
  std::int64_t value(std::size_t c, std::size_t g) const { return values_[c][g]; }
  /// Appends a ghost owned by rank `owner`, with one value per registered column.
  void add(EntityId e, EntityKind k, const Vec3& p, const Vec3& v, const Quat& q, const BodyData& b,
           int owner, std::span<const std::int64_t> values = {});
  std::optional<std::size_t> indexOf(EntityId e) const;

  std::vector<EntityId> id;
  std::vector<EntityKind> kind;
  std::vector<Vec3> pos;
  std::vector<Vec3> vel;
  std::vector<Quat> rot;
  std::vector<BodyData> body;  ///< shape and material, for rigid-body ghosts
  std::vector<int> owner;

 private:
  std::vector<GhostColumn> columns_;
  std::vector<std::vector<std::int64_t>> values_;  // per column, per ghost
  std::unordered_map<std::uint64_t, std::size_t> index_of_;
};

}  // namespace zonesim::zone
