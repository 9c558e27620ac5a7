#include "gateway/world_snapshot.h"

#include "common/interest_grid.h"
#include "gateway/world_cache.h"

namespace zonesim::gateway {

template <typename Keep>
void WorldSnapshot::ByCell::file(const std::vector<Placed>& placed, int cells, Keep keep) {
  begin.assign(std::size_t(cells) + 1, 0);
  std::size_t n = 0;
  for (const Placed& p : placed)
    if (keep(p)) ++begin[std::size_t(p.cell) + 1], ++n;
  for (std::size_t c = 1; c < begin.size(); ++c) begin[c] += begin[c - 1];
  entities.resize(n);
  fill.assign(begin.begin(), begin.end() - 1);
  for (const Placed& p : placed)
    if (keep(p)) entities[fill[std::size_t(p.cell)]++] = p.entity;
}

std::span<const SnapEntity> WorldSnapshot::ByCell::of(int cell) const {
  if (cell < 0 || std::size_t(cell) + 1 >= begin.size()) return {};
  return std::span(entities).subspan(begin[std::size_t(cell)],
                                     begin[std::size_t(cell) + 1] - begin[std::size_t(cell)]);
}

void WorldSnapshot::rebuild(const WorldCache& cache, const InterestGrid& grid, double sim_now) {
  sim_now_ = sim_now;
  // Predict once into place order, then file by cell: everything, and what changed.
  predicted_.clear();
  cache.forEach([&](std::uint64_t id, const CachedEntity& e) {
    dr::V3 p = predictedPosition(e, sim_now);
    predicted_.push_back({{id, e.version, p.x, p.z, e.state.kind}, grid.cellOf(p.x, p.z)});
  });
  all_.file(predicted_, grid.cellCount(), [](const Placed&) { return true; });
  std::uint64_t since = seen_version_;
  changed_.file(predicted_, grid.cellCount(),
                [since](const Placed& p) { return p.entity.version > since; });
  seen_version_ = cache.newestVersion();
}

std::span<const SnapEntity> WorldSnapshot::cell(int cell) const {
  return all_.of(cell);
}

std::span<const SnapEntity> WorldSnapshot::changedIn(int cell) const {
  return changed_.of(cell);
}

}  // namespace zonesim::gateway
