#pragma once
// The eight moves between grid cells and the rule for taking one, shared by the flow fields
// and the ant colonies: the same order everywhere (straight moves first), so ties between
// equally good moves break alike.

#include "ai/grid_map.h"
#include "ai/octile.h"

namespace zonesim::crowd {

/// The eight moves from a cell, straight ones first.
inline constexpr int kGridSteps[8][2] = {{1, 0}, {0, 1},  {-1, 0},  {0, -1},
                                         {1, 1}, {-1, 1}, {-1, -1}, {1, -1}};

/// The cell move k (0..7) leads to from c.
inline ai::Cell gridStep(ai::Cell c, int k) {
  return {c.x + kGridSteps[k][0], c.y + kGridSteps[k][1]};
}

/// Whether move k from c may be taken: onto open ground, and diagonally only when both cells
/// beside the move are open (no corner cutting).
inline bool gridStepAllowed(const ai::GridMap& map, ai::Cell c, int k) {
  const int nx = c.x + kGridSteps[k][0], ny = c.y + kGridSteps[k][1];
  if (!map.passable(nx, ny)) return false;
  return k < 4 || (map.passable(nx, c.y) && map.passable(c.x, ny));
}

}  // namespace zonesim::crowd
