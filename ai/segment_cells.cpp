#include "ai/segment_cells.h"

#include <algorithm>

namespace zonesim::ai {

namespace {

// The parameter span where a + t*d lies inside [c0, c0 + 1] on one axis (open or closed as
// the caller takes it); false when it never does.
bool span(double a, double d, int c0, bool closed, double& lo, double& hi) {
  if (d == 0) {
    const bool in = closed ? a >= c0 && a <= c0 + 1 : a > c0 && a < c0 + 1;
    if (!in) return false;
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

bool segmentMeetsCell(Vec2 a, Vec2 b, Cell c, CellContact contact) {
  const bool closed = contact == CellContact::Closed;
  double lx, hx, ly, hy;
  if (!span(a.x, b.x - a.x, c.x, closed, lx, hx)) return false;
  if (!span(a.y, b.y - a.y, c.y, closed, ly, hy)) return false;
  if (a == b) return true;  // a point inside on both axes
  const double lo = std::max({0.0, lx, ly}), hi = std::min({1.0, hx, hy});
  // Closed spans meet [0, 1] when lo <= hi; open ones only in more than a point.
  return closed ? lo <= hi : lo < hi;
}

}  // namespace zonesim::ai
