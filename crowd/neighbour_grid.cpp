#include "crowd/neighbour_grid.h"

#include <algorithm>
#include <limits>
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
  long long minX = std::numeric_limits<long long>::max(), minY = minX;
  long long maxX = std::numeric_limits<long long>::min(), maxY = maxX;
  for (std::size_t i = 0; i < total; ++i) {
    if (i < owned && !skip.empty() && skip[i]) continue;
    Vec2 p = posOf(i);
    long long cx = cellCoord(p.x), cy = cellCoord(p.y);
    cellX_[i] = cx;
    cellY_[i] = cy;
    minX = std::min(minX, cx);
    minY = std::min(minY, cy);
    maxX = std::max(maxX, cx);
    maxY = std::max(maxY, cy);
  }
  const bool any = minX <= maxX;
  min_x_ = any ? minX : 0;
  minY_ = any ? minY : 0;
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
  // Scatter the entries with a moving cursor per cell, reading the inputs where they lie, in
  // storage order: in random storage order, gathering them in cell order instead read a
  // position and a velocity at random and wrote an index and an id at random per entry (a
  // third of the build at 100k agents). starts_ is restored afterwards by shifting.
  entries_.resize(n);
  constexpr std::size_t kScatterAhead = 16;  // the agents' cells are in storage order: prefetch
  for (std::size_t i = 0; i < total; ++i) {
    if (i + kScatterAhead < total && cell_of_[i + kScatterAhead] >= 0) {
      const GridEntry* ahead = &entries_[starts_[cell_of_[i + kScatterAhead]]];
      __builtin_prefetch(ahead, 1);
      __builtin_prefetch(reinterpret_cast<const char*>(ahead + 1) - 1, 1);
    }
    if (cell_of_[i] < 0) continue;
    const std::int32_t k = starts_[cell_of_[i]]++;
    if (i < owned)
      entries_[k] = GridEntry{pos[i], vel[i], ids[i], static_cast<std::int32_t>(i), cell_of_[i]};
    else
      entries_[k] = GridEntry{ghosts.pos[i - owned], ghosts.vel[i - owned], ghosts.ids[i - owned],
                              -1 - static_cast<std::int32_t>(i - owned), cell_of_[i]};
  }
  for (std::size_t c = starts_.size() - 1; c > 0; --c) starts_[c] = starts_[c - 1];
  starts_[0] = 0;

  // Ids order each cell: cells hold a handful of agents, so insertion sort is the fast choice.
  for (std::size_t c = 0; c + 1 < starts_.size(); ++c) {
    const std::size_t lo = static_cast<std::size_t>(starts_[c]);
    const std::size_t hi = static_cast<std::size_t>(starts_[c + 1]);
    for (std::size_t k = lo + 1; k < hi; ++k) {
      if (!(entries_[k - 1].id > entries_[k].id)) continue;
      const GridEntry e = entries_[k];
      std::size_t j = k;
      while (j > lo && entries_[j - 1].id > e.id) {
        entries_[j] = entries_[j - 1];
        --j;
      }
      entries_[j] = e;
    }
  }
  xs_.resize(n);
  ys_.resize(n);
  const bool velocities = columns == Columns::kPositionsAndVelocities;
  vxs_.resize(velocities ? n : 0);
  vys_.resize(velocities ? n : 0);
  for (std::size_t k = 0; k < n; ++k) {
    const GridEntry& e = entries_[k];
    xs_[k] = e.pos.x;
    ys_[k] = e.pos.y;
    if (velocities) {
      vxs_[k] = e.vel.x;
      vys_[k] = e.vel.y;
    }
  }
}

}  // namespace zonesim::crowd
