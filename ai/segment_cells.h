#pragma once
// Which grid cells a straight segment passes through. A segment "crosses" a cell when it meets
// the cell's open interior: running along a cell's edge or touching its corner does not count,
// so a path may graze a wall (an agent of radius 0 on a navigation mesh does) without crossing
// it. Used to check navmesh paths against the map and to list the cells a path depends on.

#include <algorithm>
#include <cmath>
#include <utility>

#include "ai/octile.h"
#include "ai/vec2.h"

namespace zonesim::ai {

/// True when segment a-b meets the open square (c.x, c.x+1) x (c.y, c.y+1); exact for the
/// lattice points and cell centres that paths are made of (equal quotients round alike).
bool segmentCrossesCell(Vec2 a, Vec2 b, Cell c);

/// Calls fn(Cell) for every cell that segment a-b crosses, column by column (x rising, then y
/// rising): a conservative span of candidate rows per column, each checked exactly.
template <typename Fn>
void forEachCellCrossed(Vec2 a, Vec2 b, Fn&& fn) {
  if (b.x < a.x) std::swap(a, b);
  const int x_first = int(std::floor(a.x));
  const int x_last = int(std::ceil(b.x)) - 1;
  for (int x = std::min(x_first, x_last); x <= std::max(x_first, x_last); ++x) {
    // The rows the segment spans inside column [x, x+1], widened to whole cells.
    double lo_x = std::max(a.x, double(x)), hi_x = std::min(b.x, double(x + 1));
    double y0 = a.y, y1 = b.y;
    if (b.x != a.x) {
      y0 = a.y + (b.y - a.y) * ((lo_x - a.x) / (b.x - a.x));
      y1 = a.y + (b.y - a.y) * ((hi_x - a.x) / (b.x - a.x));
    }
    const int y_first = int(std::floor(std::min(y0, y1))) - 1;
    const int y_last = int(std::floor(std::max(y0, y1))) + 1;
    for (int y = y_first; y <= y_last; ++y)
      if (segmentCrossesCell(a, b, Cell{x, y})) fn(Cell{x, y});
  }
}

}  // namespace zonesim::ai
