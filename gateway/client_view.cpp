#include "gateway/client_view.h"

#include <algorithm>
#include <cmath>

#include "gateway/world_cache.h"
#include "gateway/world_snapshot.h"

namespace zonesim::gateway {

ViewDiff ClientView::diff(const std::vector<VisibleEntity>& visible) {
  ViewDiff d;
  diff(visible, d);
  return d;
}

void ClientView::diff(const std::vector<VisibleEntity>& visible, ViewDiff& d) {
  d.clear();
  ++epoch_;
  for (const VisibleEntity& v : visible) {
    auto [sent, inserted] = known_.tryEmplace(v.id, Sent{v.version, epoch_});
    if (inserted) {
      d.spawns.push_back(v.id);
      continue;
    }
    sent->epoch = epoch_;
    if (v.version > sent->version) {
      sent->version = v.version;
      d.updates.push_back(v.id);
    }
  }
  known_.eraseIf([&](std::uint64_t id, const Sent& sent) {
    if (sent.epoch == epoch_) return false;
    d.despawns.push_back(id);
    return true;
  });
  std::sort(d.spawns.begin(), d.spawns.end());
  std::sort(d.despawns.begin(), d.despawns.end());
  std::sort(d.updates.begin(), d.updates.end());
}

void ClientView::diffKnown(const std::vector<VisibleEntity>& changed, ViewDiff& d) {
  d.clear();
  for (const VisibleEntity& v : changed) {
    Sent* sent = known_.find(v.id);
    if (sent == nullptr || v.version <= sent->version) continue;
    sent->version = v.version;
    d.updates.push_back(v.id);
  }
  std::sort(d.updates.begin(), d.updates.end());
}

void selectChanged(const WorldSnapshot& snapshot, const InterestGrid& grid, const ViewPoint& at,
                   const ClientView& known, std::vector<VisibleEntity>& out) {
  out.clear();
  thread_local std::vector<int> cells;  // reused: no allocation per view once warm
  grid.cellsWithin(at.x, at.z, std::max(at.nimbus, at.keep), cells);
  bool self_listed = false;
  for (int cell : cells)
    for (const SnapEntity& e : snapshot.changedIn(cell))
      if (known.knows(e.id)) {
        out.push_back({e.id, e.version});
        self_listed = self_listed || e.id == at.self;
      }
  if (at.self != 0 && !self_listed && at.self_version != 0 && known.knows(at.self))
    out.push_back({at.self, at.self_version});
}

void selectVisible(const WorldSnapshot& snapshot, const InterestGrid& grid, const ViewPoint& at,
                   const ClientView& known, std::vector<VisibleEntity>& out) {
  out.clear();
  double keep_factor = at.nimbus > 0 ? at.keep / at.nimbus : 1.0;
  // The snapshot files entities by where they are predicted to be: the cells that meet the
  // disc are all there is to read.
  double reach = std::max(at.nimbus, at.keep);
  bool self_listed = false;
  thread_local std::vector<int> cells;  // reused: no allocation per view once warm
  grid.cellsWithin(at.x, at.z, reach, cells);
  for (int cell : cells) {
    for (const SnapEntity& e : snapshot.cell(cell)) {
      if (e.id == at.self) {
        out.push_back({e.id, e.version});
        self_listed = true;
        continue;
      }
      // Shown within the aura and nimbus, kept (if known) within both grown to keep; the hash
      // lookup only for the band in between.
      double dx = e.x - at.x, dz = e.z - at.z, d2 = dx * dx + dz * dz;
      double aura = at.aura[std::min<std::size_t>(e.kind, at.aura.size() - 1)];
      if (auraNimbusAllows(d2, aura, at.nimbus) ||
          (auraNimbusAllows(d2, aura * keep_factor, at.keep) && known.knows(e.id)))
        out.push_back({e.id, e.version});
    }
  }
  // The avatar may sit in a cell outside the disc (it just teleported or the disc is tiny).
  if (at.self != 0 && !self_listed && at.self_version != 0)
    out.push_back({at.self, at.self_version});
}

std::vector<VisibleEntity> selectVisible(const WorldCache& cache, const InterestGrid& grid,
                                         const ViewPoint& at, const ClientView& known) {
  WorldSnapshot snapshot;
  snapshot.rebuild(cache, grid, at.sim_now);
  ViewPoint with_self = at;
  const CachedEntity* self = at.self != 0 ? cache.find(at.self) : nullptr;
  with_self.self_version = self != nullptr ? self->version : 0;
  std::vector<VisibleEntity> out;
  selectVisible(snapshot, grid, with_self, known, out);
  return out;
}

}  // namespace zonesim::gateway
