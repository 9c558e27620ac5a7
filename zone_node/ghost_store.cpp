#include "zone_node/ghost_store.h"

#include <cassert>
#include <utility>

namespace zonesim::zone {

GhostColumn crowdPopulationColumn() {
  return {kCrowdPopulation, [](const EntityStore& s, std::vector<std::int64_t>& out) {
            out.resize(s.size());
            for (std::size_t i = 0; i < s.size(); ++i)
              out[i] = s.kind[i] == EntityKind::Npc ? s.npc[i].population : -1;
          }};
}

GhostColumn agentTypeColumn() {
  return {kAgentType, [](const EntityStore& s, std::vector<std::int64_t>& out) {
            out.resize(s.size());
            for (std::size_t i = 0; i < s.size(); ++i)
              out[i] = s.kind[i] == EntityKind::Npc ? s.agent[i].type : -1;
          }};
}

void GhostStore::clear() {
  id.clear();
  kind.clear();
  pos.clear();
  vel.clear();
  rot.clear();
  body.clear();
  owner.clear();
  for (std::vector<std::int64_t>& v : values_) v.clear();
  index_of_.clear();
}

std::size_t GhostStore::addColumn(GhostColumn column) {
  assert(size() == 0 && "columns are registered before the first ghost");
  if (std::optional<std::size_t> c = columnIndex(column.name)) return *c;
  columns_.push_back(std::move(column));
  values_.emplace_back();
  return columns_.size() - 1;
}

std::optional<std::size_t> GhostStore::columnIndex(std::string_view name) const {
  for (std::size_t c = 0; c < columns_.size(); ++c)
    if (columns_[c].name == name) return c;
  return std::nullopt;
}

void GhostStore::add(EntityId e, EntityKind k, const Vec3& p, const Vec3& v, const Quat& q,
                     const BodyData& b, int from, std::span<const std::int64_t> values) {
  assert((values.empty() || values.size() == columns_.size()) && "one value per column");
  index_of_[e.value] = id.size();
  id.push_back(e);
  kind.push_back(k);
  pos.push_back(p);
  vel.push_back(v);
  rot.push_back(q);
  body.push_back(b);
  owner.push_back(from);
  for (std::size_t c = 0; c < values_.size(); ++c)
    values_[c].push_back(values.empty() ? -1 : values[c]);
}

std::optional<std::size_t> GhostStore::indexOf(EntityId e) const {
  auto it = index_of_.find(e.value);
  if (it == index_of_.end()) return std::nullopt;
  return it->second;
}

}  // namespace zonesim::zone
