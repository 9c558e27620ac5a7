#include "crowd/neighbour_grid.h"

#include <algorithm>
#include <stdexcept>

namespace zonesim::crowd {

namespace {
// The dense cell array covers the box around all entries; past this many cells (64 MiB of
// offsets) the agents are too spread for the cell side and a hashed grid would be needed.
constexpr long long kMaxCells = 1LL << 24;
}  // namespace

void NeighbourGrid::build(std::span<const std::uint64_t> ids, std::span<const Vec2> pos,
                          std::span<const Vec2> vel, const GhostSpan& ghosts, double cell_size,
                          std::span<const std::uint8_t> skip, Columns columns) {
  if (!(cell_size > 0.0)) throw std::invalid_argument("NeighbourGrid: cell size must be > 0");
  cell_size_ = cell_size;
  inv_cell_ = 1.0 / cell_size;
  // Input index i: owned agents first, then ghosts (i >= owned).
  const std::size_t owned = ids.size(), total = owned + ghosts.size();
  auto posOf = [&](std::size_t i) { return i < owned ? pos[i] : ghosts.pos[i - owned]; };
  // Global cell coordinates (the same agent falls in the same cell on every rank), kept per
  // input so that each is computed once; skipped agents get cell -1.
  cellX_.resize(total);
  cellY_.resize(total);
  bool any = false;
  long long maxX = 0, maxY = 0;
  min_x_ = minY_ = 0;
  for (std::size_t i = 0; i < total; ++i) {
    if (i < owned && !skip.empty() && skip[i]) continue;
    Vec2 p = posOf(i);
    long long cx = cellCoord(p.x), cy = cellCoord(p.y);
    cellX_[i] = cx;
    cellY_[i] = cy;
    if (!any || cx < min_x_) min_x_ = cx;
    if (!any || cy < minY_) minY_ = cy;
    if (!any || cx > maxX) maxX = cx;
    if (!any || cy > maxY) maxY = cy;
    any = true;
  }
  if (!any) {
    entries_.clear();
    width_ = height_ = 0;
    return;
  }
  width_ = maxX - min_x_ + 1;
  height_ = maxY - minY_ + 1;
  if (width_ * height_ > kMaxCells)
    throw std::length_error("NeighbourGrid: agents spread over too many cells for the cell size");

  // Counting sort of input indices: count per cell, prefix sums, stable scatter.
  starts_.assign(static_cast<std::size_t>(width_ * height_ + 1), 0);
  cell_of_.resize(total);
  for (std::size_t i = 0; i < total; ++i) {
    if (i < owned && !skip.empty() && skip[i]) {
      cell_of_[i] = -1;
      continue;
    }
    cell_of_[i] = static_cast<std::int32_t>((cellY_[i] - minY_) * width_ + (cellX_[i] - min_x_));
    ++starts_[cell_of_[i] + 1];
  }
  for (std::size_t c = 1; c < starts_.size(); ++c) starts_[c] += starts_[c - 1];
  const std::size_t n = static_cast<std::size_t>(starts_.back());
  order_.resize(n);
  sort_ids_.resize(n);
  // Scatter with a moving cursor per cell; starts_ is restored afterwards by shifting.
  constexpr std::size_t kScatterAhead = 16;  // the agents' cells are in storage order: prefetch
  for (std::size_t i = 0; i < total; ++i) {
    if (i + kScatterAhead < total && cell_of_[i + kScatterAhead] >= 0) {
      const std::int32_t ahead = starts_[cell_of_[i + kScatterAhead]];
      __builtin_prefetch(&order_[ahead], 1);
      __builtin_prefetch(&sort_ids_[ahead], 1);
    }
    if (cell_of_[i] < 0) continue;
    std::int32_t k = starts_[cell_of_[i]]++;
    order_[k] = static_cast<std::int32_t>(i);
    sort_ids_[k] = i < owned ? ids[i] : ghosts.ids[i - owned];
  }
  for (std::size_t c = starts_.size() - 1; c > 0; --c) starts_[c] = starts_[c - 1];
  starts_[0] = 0;

  // Ids order each cell: cells hold a handful of agents, so insertion sort is the fast choice.
  // It runs on (id, input index) pairs; the entries are then gathered once, in order.
  for (std::size_t c = 0; c + 1 < starts_.size(); ++c) {
    const std::size_t lo = static_cast<std::size_t>(starts_[c]);
    const std::size_t hi = static_cast<std::size_t>(starts_[c + 1]);
    for (std::size_t k = lo + 1; k < hi; ++k) {
      std::uint64_t id = sort_ids_[k];
      std::int32_t at = order_[k];
      std::size_t j = k;
      while (j > lo && sort_ids_[j - 1] > id) {
        sort_ids_[j] = sort_ids_[j - 1];
        order_[j] = order_[j - 1];
        --j;
      }
      sort_ids_[j] = id;
      order_[j] = at;
    }
  }
  entries_.resize(n);
  xs_.resize(n);
  ys_.resize(n);
  const bool velocities = columns == Columns::kPositionsAndVelocities;
  vxs_.resize(velocities ? n : 0);
  vys_.resize(velocities ? n : 0);
  constexpr std::size_t kAhead = 16;  // gathers from storage order miss the cache: prefetch
  // The cell of entry k is the one whose range holds k: a cursor over starts_ finds it
  // without reading cell_of_ in storage order (a cache miss per entry).
  std::int32_t cell = 0;
  for (std::size_t k = 0; k < n; ++k) {
    while (static_cast<std::size_t>(starts_[cell + 1]) <= k) ++cell;
    if (k + kAhead < n) {
      const std::size_t a = static_cast<std::size_t>(order_[k + kAhead]);
      __builtin_prefetch(a < owned ? &pos[a] : &ghosts.pos[a - owned]);
      __builtin_prefetch(a < owned ? &vel[a] : &ghosts.vel[a - owned]);
    }
    const std::size_t i = static_cast<std::size_t>(order_[k]);
    const bool own = i < owned;
    const Vec2 p = own ? pos[i] : ghosts.pos[i - owned];
    const Vec2 v = own ? vel[i] : ghosts.vel[i - owned];
    const std::int32_t src =
        own ? static_cast<std::int32_t>(i) : -1 - static_cast<std::int32_t>(i - owned);
    entries_[k] = GridEntry{p, v, sort_ids_[k], src, cell};
    xs_[k] = p.x;
    ys_[k] = p.y;
    if (velocities) {
      vxs_[k] = v.x;
      vys_[k] = v.y;
    }
  }
}

}  // namespace zonesim::crowd
