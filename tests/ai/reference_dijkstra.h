#pragma once
// An independent, deliberately plain Dijkstra (std::priority_queue, no reuse) to check the
// optimised searches against.

#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

#include "ai/grid_map.h"
#include "common/rng.h"

namespace zonesim::ai::test {

/// Shortest octile distance without corner cutting, or -1 when unreachable.
inline double referenceDistance(const GridMap& m, Cell s, Cell g) {
  if (!m.passable(s.x, s.y) || !m.passable(g.x, g.y)) return -1;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(std::size_t(m.width() * m.height()), inf);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  dist[std::size_t(m.index(s.x, s.y))] = 0;
  q.push({0.0, m.index(s.x, s.y)});
  while (!q.empty()) {
    auto [d, i] = q.top();
    q.pop();
    if (d > dist[std::size_t(i)]) continue;
    Cell c = m.cellAt(i);
    if (c == g) return d;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0) continue;
        int nx = c.x + dx, ny = c.y + dy;
        if (!m.passable(nx, ny)) continue;
        if (dx != 0 && dy != 0 && (!m.passable(c.x + dx, c.y) || !m.passable(c.x, c.y + dy))) {
          continue;
        }
        double nd = d + (dx != 0 && dy != 0 ? std::sqrt(2.0) : 1.0);
        int ni = m.index(nx, ny);
        if (nd < dist[std::size_t(ni)]) {
          dist[std::size_t(ni)] = nd;
          q.push({nd, ni});
        }
      }
    }
  }
  return -1;
}

/// A w x h map with each cell blocked with probability `density`.
inline GridMap randomMap(int w, int h, double density, std::uint64_t seed) {
  GridMap m(w, h);
  Pcg32 rng(seed, 7);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (rng.uniform() < density) m.setPassable(x, y, false);
    }
  }
  return m;
}

/// A uniformly random passable cell (the map must have one).
inline Cell randomFreeCell(const GridMap& m, Pcg32& rng) {
  for (;;) {
    Cell c{int(rng.next() % std::uint32_t(m.width())), int(rng.next() % std::uint32_t(m.height()))};
    if (m.passable(c.x, c.y)) return c;
  }
}

}  // namespace zonesim::ai::test
