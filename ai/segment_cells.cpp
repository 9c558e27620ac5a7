#include "ai/segment_cells.h"

#include <algorithm>

namespace zonesim::ai {

namespace {

// The open parameter interval (lo, hi) where a + t*d lies strictly inside (c0, c0 + 1) on one
// axis; false when it never does.
bool openSpan(double a, double d, int c0, double& lo, double& hi) {
  if (d == 0) {
    if (!(a > c0 && a < c0 + 1)) return false;
    lo = -1e300;
    hi = 1e300;
    return true;
  }
  double t0 = (double(c0) - a) / d, t1 = (double(c0 + 1) - a) / d;
  lo = std::min(t0, t1);
  hi = std::max(t0, t1);
  return true;
}

}  // namespace

bool segmentCrossesCell(Vec2 a, Vec2 b, Cell c) {
  double lx, hx, ly, hy;
  if (!openSpan(a.x, b.x - a.x, c.x, lx, hx)) return false;
  if (!openSpan(a.y, b.y - a.y, c.y, ly, hy)) return false;
  if (a == b) return true;  // a point strictly inside
  // The open spans meet the closed [0, 1] in more than a point.
  return std::max({0.0, lx, ly}) < std::min({1.0, hx, hy});
}

}  // namespace zonesim::ai
