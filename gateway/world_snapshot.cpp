#include "gateway/world_snapshot.h"

#include "common/interest_grid.h"
#include "gateway/world_cache.h"

namespace zonesim::gateway {

void WorldSnapshot::rebuild(const WorldCache& cache, const InterestGrid& grid, double sim_now) {
  sim_now_ = sim_now;
  // Predict once into place order, then a counting sort by cell: count, prefix sums, place.
  predicted_.clear();
  cache.forEach([&](std::uint64_t id, const CachedEntity& e) {
    dr::V3 p = predictedPosition(e, sim_now);
    predicted_.push_back({{id, e.version, p.x, p.z, e.state.kind}, grid.cellOf(p.x, p.z)});
  });
  begin_.assign(std::size_t(grid.cellCount()) + 1, 0);
  for (const Placed& p : predicted_) ++begin_[std::size_t(p.cell) + 1];
  for (std::size_t c = 1; c < begin_.size(); ++c) begin_[c] += begin_[c - 1];
  entities_.resize(predicted_.size());
  fill_.assign(begin_.begin(), begin_.end() - 1);
  for (const Placed& p : predicted_) entities_[fill_[std::size_t(p.cell)]++] = p.entity;
}

std::span<const SnapEntity> WorldSnapshot::cell(int cell) const {
  if (cell < 0 || std::size_t(cell) + 1 >= begin_.size()) return {};
  return std::span(entities_).subspan(begin_[std::size_t(cell)],
                                      begin_[std::size_t(cell) + 1] - begin_[std::size_t(cell)]);
}

}  // namespace zonesim::gateway
