#include "gateway/client_view.h"

#include <algorithm>
#include <cmath>

#include "gateway/world_cache.h"

namespace zonesim::gateway {

ViewDiff ClientView::diff(const std::vector<VisibleEntity>& visible) {
  ViewDiff d;
  ++epoch_;
  for (const VisibleEntity& v : visible) {
    auto [it, inserted] = known_.try_emplace(v.id, Sent{v.version, epoch_});
    if (inserted) {
      d.spawns.push_back(v.id);
      continue;
    }
    it->second.epoch = epoch_;
    if (v.version > it->second.version) {
      it->second.version = v.version;
      d.updates.push_back(v.id);
    }
  }
  for (auto it = known_.begin(); it != known_.end();) {
    if (it->second.epoch != epoch_) {
      d.despawns.push_back(it->first);
      it = known_.erase(it);
    } else {
      ++it;
    }
  }
  std::sort(d.spawns.begin(), d.spawns.end());
  std::sort(d.despawns.begin(), d.despawns.end());
  std::sort(d.updates.begin(), d.updates.end());
  return d;
}

std::vector<VisibleEntity> selectVisible(const WorldCache& cache, const InterestGrid& grid,
                                         const ViewPoint& at, const ClientView& known) {
  std::vector<VisibleEntity> out;
  double keep_factor = at.nimbus > 0 ? at.keep / at.nimbus : 1.0;
  // Entities are indexed by the cell their zone put them in; one cell of slack covers entities
  // that moved since their last sample without crossing into a cell we do not read.
  double reach = std::max(at.nimbus, at.keep) + grid.cell_size();
  for (int cell : grid.cellsWithin(at.x, at.z, reach)) {
    cache.forEachInCell(cell, [&](std::uint64_t id, const CachedEntity& e) {
      if (id == at.self) {
        out.push_back({id, e.version});
        return;
      }
      dr::V3 now = predictedPosition(e, at.sim_now);
      double d = std::hypot(now.x - at.x, now.z - at.z);
      double aura = at.aura[std::min<std::size_t>(e.state.kind, at.aura.size() - 1)];
      bool shown = auraNimbusAllows(d, aura, at.nimbus);
      bool kept = known.knows(id) && auraNimbusAllows(d, aura * keep_factor, at.keep);
      if (shown || kept) out.push_back({id, e.version});
    });
  }
  // The avatar may sit in a cell outside the disc (it just teleported or the disc is tiny).
  if (at.self != 0) {
    const CachedEntity* self = cache.find(at.self);
    bool listed = std::any_of(out.begin(), out.end(), [&](auto& v) { return v.id == at.self; });
    if (self != nullptr && !listed) out.push_back({at.self, self->version});
  }
  return out;
}

}  // namespace zonesim::gateway
