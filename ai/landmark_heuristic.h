#pragma once
// Differential heuristic (ALT: A*, landmarks and the triangle inequality; Goldberg and
// Harrelson 2005, on grids Sturtevant et al. 2009). The exact cost d(L, c) from each of a few
// landmark cells L to every cell c is computed once by Dijkstra; then for any cells a and b,
// |d(L, a) - d(L, b)| <= d(a, b), and the largest such bound over the landmarks is an
// admissible, consistent estimate of the cost between them. On open ground the octile distance
// is as good; in a maze, where it is blind to the walls, the landmarks see the corridors: the
// bound is exact whenever one cell lies on an optimal path from the other to a landmark.
//
// Landmarks are chosen farthest first in the largest connected area: the first is the cell
// farthest from one of its cells, each next the cell farthest from all chosen so far (K + 1
// Dijkstra searches for K landmarks).
// The costs hold for the map as it was when they were built: after a change (a door) they may
// over-estimate, so a search asks validFor() and falls back to the octile distance alone.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "ai/grid_map.h"
#include "ai/octile.h"

namespace zonesim::ai {

/// Costs from a few landmark cells to every cell of a grid map, for lower bounds between cells.
class LandmarkHeuristic {
 public:
  /// Most landmarks a heuristic may hold (each costs 8 bytes a cell).
  static constexpr int kMaxLandmarks = 32;
  /// Builds `count` landmarks (1 to kMaxLandmarks; fewer when the largest area has fewer
  /// cells) for `map` as it is now; throws std::invalid_argument naming a bad count.
  LandmarkHeuristic(const GridMap& map, int count);

  /// True when built for this map object in its current version (the costs are still exact).
  bool validFor(const GridMap& map) const { return &map == map_ && map.version() == version_; }
  /// The landmark cells, in the order chosen.
  const std::vector<Cell>& landmarks() const { return landmarks_; }
  /// Memory held by the cost table, in bytes.
  std::size_t bytes() const { return costs_.size() * sizeof(std::int64_t); }

  /// The per-goal part of a query: the goal's costs (those of landmarks it cannot reach are
  /// left out: they bound nothing).
  struct Goal {
    std::vector<int> landmark;       ///< landmarks that reach the goal
    std::vector<std::int64_t> cost;  ///< their costs to it (fixed point, ai/fixed_cost.h)
  };
  /// Fills `goal` for cell (x, y) (allocating nothing once its vectors have grown).
  void prepareGoal(int x, int y, Goal& goal) const;
  /// Lower bound (fixed point) on the cost from (x, y) to the prepared goal; 0 when no landmark
  /// reaches the goal. A cell no landmark-reaching area holds is cut off from the goal, and any
  /// value bounds its (infinite) cost.
  std::int64_t bound(int x, int y, const Goal& goal) const {
    const std::int64_t* row = &costs_[std::size_t(y * width_ + x) * std::size_t(count_)];
    std::int64_t best = 0;
    for (std::size_t k = 0; k < goal.landmark.size(); ++k) {
      const std::int64_t d = row[goal.landmark[k]] - goal.cost[k];
      best = std::max(best, d < 0 ? -d : d);
    }
    return best;
  }

 private:
  const GridMap* map_;  // only compared: another map of the same size and version is not this
  int width_ = 0, height_ = 0, count_ = 0;
  std::uint64_t version_ = 0;
  std::vector<Cell> landmarks_;
  std::vector<std::int64_t> costs_;  // cell-major: [cell * count_ + landmark]; -1 unreached
};

}  // namespace zonesim::ai
