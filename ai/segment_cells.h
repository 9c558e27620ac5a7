#pragma once
// Which grid cells a straight segment meets. A segment "crosses" a cell when it meets the
// cell's open interior: running along a cell's edge or touching its corner does not count, so
// a path may graze a wall (an agent of radius 0 on a navigation mesh does) without crossing
// it. It "touches" a cell when it meets the closed square, edges and corners included: the
// cells whose closing can cut the path (a segment along the edge between two cells that both
// close passes through a wall of zero width). Used to check navmesh paths against the map and
// to list the cells a path depends on.

#include <algorithm>
#include <cmath>
#include <utility>

#include "ai/octile.h"
#include "ai/vec2.h"

namespace zonesim::ai {

/// Which part of a cell a segment must meet.
enum class CellContact {
  Interior,  ///< the open square: the segment crosses the cell
  Closed,    ///< the closed square: the segment touches the cell
};

/// True when segment a-b meets cell c as `contact` says; exact for the lattice points and cell
/// centres that paths are made of (equal quotients round alike).
bool segmentMeetsCell(Vec2 a, Vec2 b, Cell c, CellContact contact);

/// True when segment a-b meets the open square (c.x, c.x+1) x (c.y, c.y+1).
inline bool segmentCrossesCell(Vec2 a, Vec2 b, Cell c) {
  return segmentMeetsCell(a, b, c, CellContact::Interior);
}

/// Calls fn(Cell) for every cell that segment a-b meets as `contact` says, column by column (x
/// rising, then y rising): a conservative span of candidate cells per column, each checked
/// exactly.
template <typename Fn>
void forEachCellMet(Vec2 a, Vec2 b, CellContact contact, Fn&& fn) {
  if (b.x < a.x) std::swap(a, b);
  // One column and one row more on each side than the segment spans: those it touches at an
  // edge.
  const int x_first = int(std::floor(a.x)) - 1;
  const int x_last = int(std::floor(b.x)) + 1;
  for (int x = x_first; x <= x_last; ++x) {
    // The rows the segment spans inside column [x, x+1], widened to whole cells.
    const double lo_x = std::clamp(double(x), a.x, b.x), hi_x = std::clamp(double(x + 1), a.x, b.x);
    double y0 = a.y, y1 = b.y;
    if (b.x != a.x) {
      y0 = a.y + (b.y - a.y) * ((lo_x - a.x) / (b.x - a.x));
      y1 = a.y + (b.y - a.y) * ((hi_x - a.x) / (b.x - a.x));
    }
    const int y_first = int(std::floor(std::min(y0, y1))) - 1;
    const int y_last = int(std::floor(std::max(y0, y1))) + 1;
    for (int y = y_first; y <= y_last; ++y)
      if (segmentMeetsCell(a, b, Cell{x, y}, contact)) fn(Cell{x, y});
  }
}

/// forEachCellMet for the cells the segment crosses.
template <typename Fn>
void forEachCellCrossed(Vec2 a, Vec2 b, Fn&& fn) {
  forEachCellMet(a, b, CellContact::Interior, std::forward<Fn>(fn));
}

}  // namespace zonesim::ai
