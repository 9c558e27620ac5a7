#include "crowd/map_frame.h"

#include <cmath>

namespace zonesim::crowd {

bool walkable(const ai::GridMap& map, const MapFrame& frame, Vec2 p) {
  ai::Cell c = frame.cellOf(p);
  return map.passable(c.x, c.y);
}

namespace {
// A step between cells a and b (8-neighbours or equal) that does not enter a blocked cell
// nor squeeze diagonally between two blocked ones. Moving inside one cell is always allowed: an
// agent on a cell that closed under it (a door) must be able to walk out.
bool stepAllowed(const ai::GridMap& map, ai::Cell a, ai::Cell b) {
  if (a == b) return true;
  if (!map.passable(b.x, b.y)) return false;
  if (a.x != b.x && a.y != b.y) return map.passable(b.x, a.y) && map.passable(a.x, b.y);
  return true;
}
}  // namespace

namespace {
Vec2 slideOnce(const ai::GridMap& map, const MapFrame& frame, Vec2 from, Vec2 to, Vec2& vel) {
  ai::Cell a = frame.cellOf(from);
  if (stepAllowed(map, a, frame.cellOf(to))) return to;
  Vec2 xOnly{to.x, from.y}, yOnly{from.x, to.y};
  // Slide along whichever axis is open; prefer the longer component so that motion continues
  // along the wall the agent is travelling beside.
  bool preferX = std::fabs(to.x - from.x) >= std::fabs(to.y - from.y);
  for (int k = 0; k < 2; ++k) {
    bool tryX = (k == 0) == preferX;
    Vec2 cand = tryX ? xOnly : yOnly;
    if (stepAllowed(map, a, frame.cellOf(cand))) {
      (tryX ? vel.y : vel.x) = 0.0;
      return cand;
    }
  }
  vel = Vec2{};
  return from;
}
}  // namespace

Vec2 slideMove(const ai::GridMap& map, const MapFrame& frame, Vec2 from, Vec2 to, Vec2& vel) {
  // Long moves (large LOD steps) are cut into sub-moves of under half a cell, so that no move
  // jumps over a blocked cell.
  Vec2 d = to - from;
  // Moves of a tick are far shorter than half a cell: one piece, no square root. The bound has
  // a margin of 1e-9 so that every move taken here has length(d) < half a cell exactly as the
  // general path below would compute it.
  const double half = 0.5 * frame.cell_size;
  if (lengthSq(d) < half * half * (1.0 - 1e-9)) return slideOnce(map, frame, from, to, vel);
  double len = length(d);
  int pieces = len < 0.5 * frame.cell_size ? 1 : int(std::ceil(len / (0.45 * frame.cell_size)));
  Vec2 piece = d * (1.0 / pieces), at = from;
  for (int k = 0; k < pieces; ++k) {
    Vec2 target = k + 1 == pieces ? to : at + piece;
    Vec2 before = at;
    at = slideOnce(map, frame, at, target, vel);
    if (at == before) break;
    // A slide changes direction: keep going along the slid direction only.
    if (k + 1 < pieces && !(at == target)) {
      Vec2 slid = at - before;
      piece = Vec2{slid.x == 0 ? 0 : piece.x, slid.y == 0 ? 0 : piece.y};
      to = at + piece * double(pieces - k - 1);
    }
  }
  return at;
}

bool lineOfSight(const ai::GridMap& map, const MapFrame& frame, Vec2 a, Vec2 b) {
  // Amanatides-Woo traversal in cell units.
  double ax = (a.x - frame.origin.x) / frame.cell_size,
         ay = (a.y - frame.origin.y) / frame.cell_size;
  double bx = (b.x - frame.origin.x) / frame.cell_size,
         by = (b.y - frame.origin.y) / frame.cell_size;
  int x = int(std::floor(ax)), y = int(std::floor(ay));
  const int xEnd = int(std::floor(bx)), yEnd = int(std::floor(by));
  if (!map.passable(x, y)) return false;
  const double dx = bx - ax, dy = by - ay;
  const int sx = dx > 0 ? 1 : -1, sy = dy > 0 ? 1 : -1;
  const double tdx = dx != 0 ? std::fabs(1.0 / dx) : 1e300;
  const double tdy = dy != 0 ? std::fabs(1.0 / dy) : 1e300;
  double tx = dx != 0 ? ((sx > 0 ? x + 1 - ax : ax - x) * tdx) : 1e300;
  double ty = dy != 0 ? ((sy > 0 ? y + 1 - ay : ay - y) * tdy) : 1e300;
  int guard = std::abs(xEnd - x) + std::abs(yEnd - y) + 2;
  while ((x != xEnd || y != yEnd) && guard-- > 0) {
    if (std::fabs(tx - ty) < 1e-12) {
      // Through a corner: both side cells must be open (no squeezing between blocks).
      if (!map.passable(x + sx, y) || !map.passable(x, y + sy)) return false;
      x += sx;
      y += sy;
      tx += tdx;
      ty += tdy;
    } else if (tx < ty) {
      x += sx;
      tx += tdx;
    } else {
      y += sy;
      ty += tdy;
    }
    if (!map.passable(x, y)) return false;
  }
  return true;
}

}  // namespace zonesim::crowd
