#include "gateway/world_snapshot.h"

#include "gateway/world_cache.h"

namespace zonesim::gateway {

void WorldSnapshot::rebuild(const WorldCache& cache, int cell_count, double sim_now) {
  sim_now_ = sim_now;
  // Counting sort by cell: count, prefix sums, place.
  begin_.assign(std::size_t(cell_count) + 1, 0);
  cache.forEach([&](std::uint64_t, const CachedEntity& e) {
    if (e.cell >= 0 && e.cell < cell_count) ++begin_[std::size_t(e.cell) + 1];
  });
  for (std::size_t c = 1; c < begin_.size(); ++c) begin_[c] += begin_[c - 1];
  entities_.resize(begin_.back());
  std::vector<std::uint32_t>& next = fill_;
  next.assign(begin_.begin(), begin_.end() - 1);
  cache.forEach([&](std::uint64_t id, const CachedEntity& e) {
    if (e.cell < 0 || e.cell >= cell_count) return;
    dr::V3 p = predictedPosition(e, sim_now);
    entities_[next[std::size_t(e.cell)]++] = {id, e.version, p.x, p.z, e.state.kind};
  });
}

std::span<const SnapEntity> WorldSnapshot::cell(int cell) const {
  if (cell < 0 || std::size_t(cell) + 1 >= begin_.size()) return {};
  return std::span(entities_).subspan(begin_[std::size_t(cell)],
                                      begin_[std::size_t(cell) + 1] - begin_[std::size_t(cell)]);
}

}  // namespace zonesim::gateway
