#include "zone_node/crowd/neighbour_grid.h"

#include <algorithm>
#include <stdexcept>

namespace zonesim::crowd {

namespace {
// The dense cell array covers the box around all entries; past this many cells (64 MiB of
// offsets) the agents are too spread for the cell side and a hashed grid would be needed.
constexpr long long kMaxCells = 1LL << 24;
}  // namespace

void NeighbourGrid::add(std::uint64_t id, Vec2 p, Vec2 v, std::int32_t src) {
  staged_.push_back(GridEntry{p, v, id, src, 0});
}

void NeighbourGrid::build(std::span<const std::uint64_t> ids, std::span<const Vec2> pos,
                          std::span<const Vec2> vel, const GhostSpan& ghosts, double cellSize,
                          std::span<const std::uint8_t> skip) {
  if (!(cellSize > 0.0)) throw std::invalid_argument("NeighbourGrid: cell size must be > 0");
  cellSize_ = cellSize;
  invCell_ = 1.0 / cellSize;
  staged_.clear();
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (skip.empty() || !skip[i]) add(ids[i], pos[i], vel[i], static_cast<std::int32_t>(i));
  for (std::size_t i = 0; i < ghosts.size(); ++i)
    add(ghosts.ids[i], ghosts.pos[i], ghosts.vel[i], -1 - static_cast<std::int32_t>(i));
  entries_.resize(staged_.size());
  if (staged_.empty()) {
    width_ = height_ = 0;
    return;
  }

  // Global cell coordinates: the same agent falls in the same cell on every rank.
  long long maxX = 0, maxY = 0;
  minX_ = minY_ = 0;
  for (std::size_t k = 0; k < staged_.size(); ++k) {
    long long cx = cellCoord(staged_[k].pos.x), cy = cellCoord(staged_[k].pos.y);
    if (k == 0 || cx < minX_) minX_ = cx;
    if (k == 0 || cy < minY_) minY_ = cy;
    if (k == 0 || cx > maxX) maxX = cx;
    if (k == 0 || cy > maxY) maxY = cy;
  }
  width_ = maxX - minX_ + 1;
  height_ = maxY - minY_ + 1;
  if (width_ * height_ > kMaxCells)
    throw std::length_error("NeighbourGrid: agents spread over too many cells for the cell size");

  // Counting sort: count per cell, prefix sums, stable scatter.
  starts_.assign(static_cast<std::size_t>(width_ * height_ + 1), 0);
  for (GridEntry& e : staged_) {
    e.cell = static_cast<std::int32_t>((cellCoord(e.pos.y) - minY_) * width_ +
                                       (cellCoord(e.pos.x) - minX_));
    ++starts_[e.cell + 1];
  }
  for (std::size_t c = 1; c < starts_.size(); ++c) starts_[c] += starts_[c - 1];
  // Scatter with a moving cursor per cell; starts_ is restored afterwards by shifting.
  for (const GridEntry& e : staged_) entries_[starts_[e.cell]++] = e;
  for (std::size_t c = starts_.size() - 1; c > 0; --c) starts_[c] = starts_[c - 1];
  starts_[0] = 0;

  // Ids order each cell: cells hold a handful of agents, so insertion sort is the fast choice.
  const std::size_t n = entries_.size();
  for (std::size_t k = 1; k < n; ++k) {
    GridEntry e = entries_[k];
    std::size_t j = k;
    while (j > 0 && entries_[j - 1].cell == e.cell && entries_[j - 1].id > e.id) {
      entries_[j] = entries_[j - 1];
      --j;
    }
    entries_[j] = e;
  }
  xs_.resize(n);
  ys_.resize(n);
  vxs_.resize(n);
  vys_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    xs_[k] = entries_[k].pos.x;
    ys_[k] = entries_[k].pos.y;
    vxs_[k] = entries_[k].vel.x;
    vys_[k] = entries_[k].vel.y;
  }
}

}  // namespace zonesim::crowd
