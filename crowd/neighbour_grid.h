#pragma once
// Uniform-grid neighbour search: a counting sort of owned agents and ghosts into square cells
// of a fixed side, on global cell coordinates (floor(x / side)), with each cell's entries
// sorted by id. A query visits the cells overlapping its box row by row, then each cell's
// entries by id: an order fixed by positions and ids alone, so sums over neighbours are
// bitwise the same whatever order the caller stored its agents in and whichever rank owns
// them (given that the ghosts cover the query radius). Entries are copied into cell order, so
// a query reads contiguous memory; owned agents are visited in cell order by the steps, which
// keeps the neighbours of consecutive agents in cache.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "crowd/agents.h"

namespace zonesim::crowd {

/// One agent as stored by the grid, in cell order.
struct GridEntry {
  Vec2 pos;           ///< position
  Vec2 vel;           ///< velocity
  std::uint64_t id;   ///< the agent's id
  std::int32_t src;   ///< index in the owned span, or -1 - index in the ghost span
  std::int32_t cell;  ///< dense cell index (row-major over the occupied box)
};

/// Cells over owned agents and ghosts; rebuilt every step, allocation-free once warm.
class NeighbourGrid {
 public:
  /// Which coordinate arrays build() fills: the flock's lane-wide sums read the velocities
  /// too; the flow crowd reads positions only (at 100k agents, not writing the 16 bytes an
  /// agent it never reads takes 0.94 to 0.97 of the time of its bench's runs).
  enum class Columns { kPositionsAndVelocities, kPositions };

  /// Sorts `agents` and `ghosts` into cells of side `cell_size` (> 0). Owned agents with a
  /// non-zero `skip` flag (an empty span skips none) are left out: nobody sees them. With
  /// Columns::kPositions, vxs() and vys() are empty.
  void build(std::span<const std::uint64_t> ids, std::span<const Vec2> pos,
             std::span<const Vec2> vel, const GhostSpan& ghosts, double cell_size,
             std::span<const std::uint8_t> skip = {},
             Columns columns = Columns::kPositionsAndVelocities);
  /// Convenience: build from an AgentSpan.
  void build(const AgentSpan& agents, const GhostSpan& ghosts, double cell_size) {
    build(agents.ids, agents.pos, agents.vel, ghosts, cell_size);
  }

  /// All entries in cell order (owned and ghosts).
  std::span<const GridEntry> entries() const { return entries_; }

  /// Calls f(const GridEntry&) for every entry of a cell that overlaps the disc of `radius`
  /// around `p` (each row of cells is clipped to the disc's chord), cells row by row, entries
  /// by id (the canonical order). Entries outside the disc are visited too: the caller
  /// filters by distance.
  template <class F>
  void forEachNear(Vec2 p, double radius, F&& f) const {
    // Cells of one row are contiguous in entries_, so a row is one linear scan.
    forEachRowNear(p, radius, [&](std::int32_t begin, std::int32_t end) {
      for (std::int32_t k = begin; k < end; ++k) f(entries_[k]);
    });
  }

  /// Calls f(begin, end) for each row of cells that overlaps the disc of `radius` around
  /// `p`, clipped to the disc's chord, in the same canonical order as forEachNear; the range
  /// indexes entries() and the coordinate arrays xs() .. vys(), for vectorised loops.
  template <class F>
  void forEachRowNear(Vec2 p, double radius, F&& f) const {
    forEachRowNearAll(&p, 1, radius, f);
  }

  /// As forEachRowNear for two discs at once: per row, the smallest range of cells holding
  /// both chords, rows in order. Each disc's own entries come in its canonical order, with
  /// extra entries (out of its reach) in between: a step can sum for two agents in one pass.
  template <class F>
  void forEachRowNearEither(Vec2 a, Vec2 b, double radius, F&& f) const {
    const Vec2 p[2] = {a, b};
    forEachRowNearAll(p, 2, radius, f);
  }

  /// As forEachRowNear, but each row's range covers the cells of the square of half side
  /// `radius` around `p`: a superset of the disc's chords (the extra cells lie outside the
  /// disc), so the entries within the disc come in the same canonical order. No square root
  /// per row: for callers that filter by distance anyway and whose discs span few cells.
  template <class F>
  void forEachRowInBox(Vec2 p, double radius, F&& f) const {
    if (entries_.empty()) return;
    const long long cy0 = std::max(cellCoord(p.y - radius) - minY_, 0LL);
    const long long cy1 = std::min(cellCoord(p.y + radius) - minY_, height_ - 1);
    const long long cx0 = std::max(cellCoord(p.x - radius) - min_x_, 0LL);
    const long long cx1 = std::min(cellCoord(p.x + radius) - min_x_, width_ - 1);
    if (cx0 > cx1) return;
    for (long long cy = cy0; cy <= cy1; ++cy) {
      const std::int32_t* row = starts_.data() + cy * width_;
      if (row[cx0] < row[cx1 + 1]) f(row[cx0], row[cx1 + 1]);
    }
  }

  /// As forEachRowNearEither for the discs around `p[0 .. n)` (n >= 1).
  template <class F>
  void forEachRowNearAll(const Vec2* p, int n, double radius, F&& f) const {
    if (entries_.empty()) return;
    double y_lo = p[0].y, yHi = p[0].y;
    for (int i = 1; i < n; ++i) {
      y_lo = std::min(y_lo, p[i].y);
      yHi = std::max(yHi, p[i].y);
    }
    long long cy0 = cellCoord(y_lo - radius) - minY_, cy1 = cellCoord(yHi + radius) - minY_;
    if (cy0 < 0) cy0 = 0;
    if (cy1 >= height_) cy1 = height_ - 1;
    for (long long cy = cy0; cy <= cy1; ++cy) {
      long long cx0 = 1, cx1 = 0;  // empty
      for (int i = 0; i < n; ++i) {
        long long x0, x1;
        chord(p[i], radius, cy, x0, x1);
        if (x0 > x1) continue;
        if (cx0 > cx1) {
          cx0 = x0;
          cx1 = x1;
        } else {
          cx0 = std::min(cx0, x0);
          cx1 = std::max(cx1, x1);
        }
      }
      if (cx0 > cx1) continue;
      if (cx0 < 0) cx0 = 0;
      if (cx1 >= width_) cx1 = width_ - 1;
      if (cx0 > cx1) continue;
      const std::int32_t* row = starts_.data() + cy * width_;
      if (row[cx0] < row[cx1 + 1]) f(row[cx0], row[cx1 + 1]);
    }
  }

  /// The cell ranges of the rows near discs of `radius` around p[0..n), as (begin, end) pairs
  /// in `out`; returns how many, or -1 when there are more than `cap` (for loops that cannot
  /// take a callback, such as code compiled for another instruction set). Each row's range is
  /// the cells from the leftmost disc's left edge to the rightmost disc's right edge at the
  /// row's nearest point to any of the discs: a superset of the union of the chords that
  /// forEachRowNearAll visits (the extra cells lie outside every disc), found with one square
  /// root per row. For groups of nearby discs, whose loops filter by distance.
  int rowRangesNearBox(const Vec2* p, int n, double radius, std::int32_t* out, int cap) const {
    if (entries_.empty()) return 0;
    double x_lo = p[0].x, xHi = p[0].x, y_lo = p[0].y, yHi = p[0].y;
    for (int i = 1; i < n; ++i) {
      x_lo = std::min(x_lo, p[i].x);
      xHi = std::max(xHi, p[i].x);
      y_lo = std::min(y_lo, p[i].y);
      yHi = std::max(yHi, p[i].y);
    }
    long long cy0 = std::max(cellCoord(y_lo - radius) - minY_, 0LL);
    long long cy1 = std::min(cellCoord(yHi + radius) - minY_, height_ - 1);
    int count = 0;
    for (long long cy = cy0; cy <= cy1; ++cy) {
      double rowLo = double(cy + minY_) * cell_size_, rowHi = rowLo + cell_size_;
      // The smallest gap between the row and a disc centre bounds every chord in the row.
      double gap = yHi < rowLo ? rowLo - yHi : (y_lo > rowHi ? y_lo - rowHi : 0.0);
      double half = std::sqrt(std::max(0.0, radius * radius - gap * gap));
      long long cx0 = std::max(cellCoord(x_lo - half) - min_x_, 0LL);
      long long cx1 = std::min(cellCoord(xHi + half) - min_x_, width_ - 1);
      if (cx0 > cx1) continue;
      const std::int32_t* row = starts_.data() + cy * width_;
      if (row[cx0] == row[cx1 + 1]) continue;
      if (count == cap) return -1;
      out[2 * count] = row[cx0];
      out[2 * count + 1] = row[cx1 + 1];
      ++count;
    }
    return count;
  }

  /// x of every entry, in cell order (structure of arrays for vectorised neighbour loops).
  const double* xs() const { return xs_.data(); }
  /// y of every entry.
  const double* ys() const { return ys_.data(); }
  /// Velocity x of every entry (unless built with Columns::kPositions).
  const double* vxs() const { return vxs_.data(); }
  /// Velocity y of every entry.
  const double* vys() const { return vys_.data(); }

  /// Row of a dense cell index (entries of one row are contiguous).
  std::int32_t rowOf(std::int32_t cell) const { return static_cast<std::int32_t>(cell / width_); }

  /// Side of the cells.
  double cell_size() const { return cell_size_; }

 private:
  // floor() without the libm call (baseline x86-64 has no rounding instruction to inline);
  // exact for |v| < 2^63, far beyond any world.
  long long cellCoord(double v) const {
    double s = v * inv_cell_;
    long long t = static_cast<long long>(s);
    return t - (s < static_cast<double>(t));
  }
  // Cells [x0, x1] of row cy (relative to the box) that the disc's chord crosses, unclipped;
  // x0 > x1 when the row lies outside the disc's rows.
  void chord(Vec2 p, double radius, long long cy, long long& x0, long long& x1) const {
    if (cy < cellCoord(p.y - radius) - minY_ || cy > cellCoord(p.y + radius) - minY_) {
      x0 = 1;
      x1 = 0;
      return;
    }
    double rowLo = double(cy + minY_) * cell_size_, rowHi = rowLo + cell_size_;
    double gap = p.y < rowLo ? rowLo - p.y : (p.y > rowHi ? p.y - rowHi : 0.0);
    double half = std::sqrt(std::max(0.0, radius * radius - gap * gap));
    x0 = cellCoord(p.x - half) - min_x_;
    x1 = cellCoord(p.x + half) - min_x_;
  }

  double cell_size_ = 1.0;
  double inv_cell_ = 1.0;
  long long min_x_ = 0, minY_ = 0;
  long long width_ = 0, height_ = 0;
  std::vector<std::int32_t> starts_;         // width_*height_ + 1 prefix sums
  std::vector<long long> cellX_, cellY_;     // input order (owned, then ghosts): coordinates
  std::vector<std::int32_t> cell_of_;        // input order: dense cell, -1 when skipped
  std::vector<GridEntry> entries_;           // cell order
  std::vector<double> xs_, ys_, vxs_, vys_;  // entries_ as structure of arrays
};

}  // namespace zonesim::crowd
