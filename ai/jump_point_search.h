#pragma once
// Jump point search (Harabor and Grastien) on an 8-connected grid without corner cutting: the
// same optimal paths as A* (GridSearch), found by expanding only jump points. From a node, a
// search runs straight or diagonally ("jumps") past every cell whose neighbours an optimal path
// could reach as cheaply without it, and stops at the goal or at a cell with a forced
// neighbour: one beside the line whose cell behind is blocked, so it is reachable optimally
// only through this cell. Without corner cutting a diagonal move has no forced neighbours; a
// diagonal jump stops where a straight jump from it along either of its components would stop.
//
// JPS+ (Rabin, Game AI Pro 2) precomputes, for every cell and each of the 8 directions, how far
// the jump goes: the distance to the next jump point (positive) or the number of open cells
// before a wall (zero or negative). A jump is then one table read; the goal, which is a jump
// point of every search, is caught by checking whether it lies within a jump's reach. The
// tables are rebuilt when the map changes (a door), in O(8 cells).

#include <cstdint>
#include <vector>

#include "ai/grid_map.h"
#include "ai/grid_path.h"
#include "ai/grid_search.h"

namespace zonesim::ai {

/// Reusable optimal grid searcher bound to one map (which may change between searches).
class JumpPointSearch {
 public:
  /// Scanning jumps cell by cell, or reading them from JPS+ tables.
  enum class Jumps { Scanned, Precomputed };
  /// Sizes the node records for `map`; the map must outlive the searcher.
  explicit JumpPointSearch(const GridMap& map, Jumps jumps = Jumps::Scanned);

  /// Optimal 8-connected path without corner cutting, every cell listed; false (and `out`
  /// empty) when there is none.
  bool findPath(Cell start, Cell goal, GridPath& out);
  /// Counters of the last search (expanded: jump points taken off the open list).
  const SearchStats& lastStats() const { return stats_; }

 private:
  struct Node {
    std::int64_t g;  // fixed point (ai/fixed_cost.h)
    std::int32_t parent;
    std::uint32_t stamp;  // == generation_: open, generation_ + 1: closed, else untouched
  };
  struct HeapEntry {
    std::int64_t f;
    std::int64_t g;
    std::int32_t idx;
  };

  /// Walkable with the map's border counted as wall: cells are read from a copy padded by one
  /// blocked cell on every side, so the jump loops need no bounds checks.
  bool walkable(int x, int y) const {
    return open_[padded(x, y)] != 0;
  }
  /// Refreshes the padded copy (and the JPS+ tables) when the map changed.
  void syncCells();
  /// JPS+: fills distance_ from the padded cells.
  void precompute();
  /// The next node along (dx, dy) from (x, y), by scanning or by table, or -1.
  int jump(int x, int y, int dx, int dy) const;
  /// Padded index of a cell.
  std::size_t padded(int x, int y) const {
    return std::size_t(y + 1) * std::size_t(padded_width_) + std::size_t(x + 1);
  }
  /// The first jump point moving from (x, y) along a cardinal (dx, dy), or -1.
  int jumpStraight(int x, int y, int dx, int dy) const;
  /// The first jump point moving from (x, y) along a diagonal (dx, dy), or -1.
  int jumpDiagonal(int x, int y, int dx, int dy) const;
  void beginSearch();
  void tracePath(int goal, GridPath& out) const;

  const GridMap& map_;
  std::vector<std::uint8_t> open_;  // (width + 2) x (height + 2), border blocked
  int padded_width_ = 0;
  Jumps jumps_;
  // JPS+: per direction (0 E, 1 W, 2 S, 3 N, 4 SE, 5 SW, 6 NE, 7 NW) and padded cell, the
  // distance to the next jump point (> 0) or minus the open cells before a wall (<= 0).
  std::vector<std::int32_t> distance_[8];
  std::uint64_t synced_version_ = ~std::uint64_t(0);
  std::vector<Node> nodes_;
  std::vector<HeapEntry> heap_;
  std::uint32_t generation_ = 0;
  int goal_x_ = 0, goal_y_ = 0;
  SearchStats stats_;
};

}  // namespace zonesim::ai
