#include "crowd/overlap.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace zonesim::crowd {

Overlap deepestOverlap(const NeighbourGrid& grid, double radius) {
  if (!(radius > 0.0)) throw std::invalid_argument("deepestOverlap: radius must be positive");
  const double reach = 2.0 * radius, reach2 = reach * reach;
  Overlap out;
  double closest2 = reach2;
  for (const GridEntry& e : grid.entries()) {
    if (e.src < 0) continue;
    grid.forEachNear(e.pos, reach, [&](const GridEntry& o) {
      // Each owned pair once (from its lower id); an owned-ghost pair from the owned side.
      if (o.src >= 0 && o.id <= e.id) return;
      const double d2 = lengthSq(o.pos - e.pos);
      if (d2 >= reach2) return;
      ++out.pairs;
      if (d2 < closest2) {
        closest2 = d2;
        out.a = std::min(e.id, o.id);
        out.b = std::max(e.id, o.id);
        out.at = (e.pos + o.pos) * 0.5;
      }
    });
  }
  if (out.pairs > 0) out.depth = reach - std::sqrt(closest2);
  return out;
}

}  // namespace zonesim::crowd
