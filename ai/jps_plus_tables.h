#pragma once
// JPS+ (Rabin, Game AI Pro 2): for every cell and each of the 8 directions, how far a jump from
// it goes, so that a jump is one table read: the distance to the next jump point (positive) or
// minus the number of open cells before a wall (zero or negative). Jump points are those of
// JumpPointSearch without corner cutting: a straight move stops at a forced neighbour, a
// diagonal one where a straight jump along either of its components would stop.

#include <cstdint>
#include <vector>

#include "ai/bit_grid.h"

namespace zonesim::ai {

/// Per-direction jump distances of every cell of a map.
class JpsPlusTables {
 public:
  /// Direction index of (dx, dy): 0 E, 1 W, 2 S, 3 N, 4 SE, 5 SW, 6 NE, 7 NW.
  static int direction(int dx, int dy) {
    static constexpr int kIndex[9] = {7, 3, 6, 1, -1, 0, 5, 2, 4};  // by (dy + 1) * 3 + dx + 1
    return kIndex[(dy + 1) * 3 + dx + 1];
  }

  /// Recomputes every table from `rows` (the map's walkable bits, not transposed).
  void build(const BitGrid& rows);
  /// Distance from (x, y) along direction `d` to the next jump point (> 0), or minus the open
  /// cells before a wall (<= 0).
  std::int32_t distance(int d, int x, int y) const { return table_[d][padded(x, y)]; }

 private:
  std::size_t padded(int x, int y) const {
    return std::size_t(y + 1) * std::size_t(width_ + 2) + std::size_t(x + 1);
  }

  int width_ = 0;
  std::vector<std::int32_t> table_[8];  // (width + 2) x (height + 2), border 0
};

}  // namespace zonesim::ai
