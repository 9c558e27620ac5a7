#pragma once
// Jump point search (Harabor and Grastien) on an 8-connected grid without corner cutting: the
// same optimal paths as A* (GridSearch), found by expanding only jump points. From a node, a
// search runs straight or diagonally ("jumps") past every cell whose neighbours an optimal path
// could reach as cheaply without it, and stops at the goal or at a cell with a forced
// neighbour: one beside the line whose cell behind is blocked, so it is reachable optimally
// only through this cell. Without corner cutting a diagonal move has no forced neighbours; a
// diagonal jump stops where a straight jump from it along either of its components would stop.
//
// Straight jumps scan 55 cells at a time over bit-packed rows (and columns, for vertical
// jumps): see BitGrid. Diagonal jumps do not stop at those intermediate cells (Harabor and
// Grastien 2014): the straight jumps' targets become successors of the node jumped from
// directly, reached by the diagonal then the straight run, which keeps the open list short.
// JPS+ (JpsPlusTables) reads the jumps from precomputed tables instead of scanning them; the
// tables and bits are rebuilt when the map changes (a door), in O(cells).
//
// In a corridor (a 1-wide maze) every bend is a jump point, yet a path through a bend can only
// go on round it: a straight jump that stops at one turns and goes on within the same
// expansion, the bend recorded with its cost and parent for the path but never put on the open
// list; a bend already passed as cheaply ends the jump (it would only repeat or go back).
//
// The estimate of the cost to the goal is the octile distance, or, given a LandmarkHeuristic
// built for the map as it is, the larger of that and the landmarks' bound: both consistent, so
// the paths stay optimal, and in a maze, where the octile distance is blind to the walls, far
// fewer jump points are expanded.
//
// Node records (g, parent) and their 2-byte generation stamps (so that nothing is cleared per
// query) are indexed by y << shift | x: coordinates come back with a shift and a mask instead
// of a division. The open list is JpsOpenList.

#include <algorithm>
#include <cstdint>
#include <vector>

#include "ai/bit_grid.h"
#include "ai/fixed_cost.h"
#include "ai/grid_map.h"
#include "ai/grid_path.h"
#include "ai/grid_search.h"
#include "ai/jps_open_list.h"
#include "ai/jps_plus_tables.h"
#include "ai/landmark_heuristic.h"

namespace zonesim::ai {

/// Reusable optimal grid searcher bound to one map (which may change between searches).
class JumpPointSearch {
 public:
  /// Scanning jumps over bit-packed cells, or reading them from JPS+ tables.
  enum class Jumps { Scanned, Precomputed };
  /// Sizes the node records for `map`; the map must outlive the searcher, and so must
  /// `landmarks` (may be null; shared by several searchers), used while valid for the map.
  explicit JumpPointSearch(const GridMap& map, Jumps jumps = Jumps::Scanned,
                           const LandmarkHeuristic* landmarks = nullptr);

  /// Optimal 8-connected path without corner cutting, every cell listed; false (and `out`
  /// empty) when there is none.
  bool findPath(Cell start, Cell goal, GridPath& out);
  /// Estimates with `landmarks` too while they are valid for the map (null: octile alone);
  /// they must outlive the searcher.
  void useLandmarks(const LandmarkHeuristic* landmarks) { landmarks_ = landmarks; }
  /// Counters of the last search (expanded: jump points taken off the open list).
  const SearchStats& lastStats() const { return stats_; }

 private:
  // A cell's search state is its stamp, kept apart from the rest of its record: a jump's
  // target is first only tested (open? closed? untouched?), and 2 bytes a cell (512 KB on a
  // 512 x 512 map) stay in the L2 cache where 16-byte records missed it.
  struct Node {
    std::int64_t g;  // fixed point (ai/fixed_cost.h); valid when the stamp is this search's
    std::int32_t parent;
  };
  // Stamps relative to generation_: open, closed, a bend passed; anything else is untouched.
  enum : std::uint16_t { kOpen = 0, kClosed = 1, kBend = 2, kStamps = 3 };

  /// Walkable, the map's border counted as wall.
  bool walkable(int x, int y) const { return rows_.walkable(y, x); }
  /// Starts a search: new stamps (every stamp reset when they wrap), an empty open list.
  void beginSearch();
  /// Lower bound on the cost from (x, y) to the goal (fixed point).
  std::int64_t estimate(int x, int y) const {
    const std::int64_t octile = octileFixed(x - goal_x_, y - goal_y_);
    if (!use_landmarks_) return octile;
    return std::max(octile, landmarks_->bound(x, y, goal_landmarks_));
  }
  /// Node index of a cell.
  int node(int x, int y) const { return (y << shift_) | x; }
  /// Refreshes the bits (and the JPS+ tables) when the map changed.
  void syncCells();
  /// A straight jump's end: the node reached (-1: none) and, for a bend, the way on.
  struct Jump {
    int to;
    int turn_x, turn_y;  // both 0 unless `to` is a bend
  };
  /// The jump point reached moving straight (one of dx, dy zero) from (x, y).
  Jump jumpStraight(int x, int y, int dx, int dy) const;
  /// The next cell along diagonal (dx, dy) from (x, y) from which straight jumps must be
  /// tried (every open step when scanning; a JPS+ jump point, or the goal's row or column),
  /// written to (x, y); false when the diagonal is blocked first.
  bool stepDiagonal(int& x, int& y, int dx, int dy) const;
  /// True when (x, y) is a bend: one open neighbour across each axis, the cell between them
  /// blocked, so paths through it only turn there. `dx, dy`: the way in; the way on is
  /// written to `turn_x, turn_y`.
  bool isBend(int x, int y, int dx, int dy, int& turn_x, int& turn_y) const;
  /// Expands the node at (x, y): jumps along its pruned directions and relaxes what they reach.
  void expand(int idx, int x, int y);
  /// Follows a straight jump from (x, y), reached at cost g with `from` its last recorded
  /// cell, that found `jump`: round any bends, then relaxes the jump point it ends at.
  void relaxJump(int from, int x, int y, std::int64_t g, Jump jump);
  /// Opens or improves node `to` at cost g, its parent `from` (its path from there is the
  /// canonical one: diagonal first, then straight).
  void relax(int from, int to, std::int64_t g);
  void tracePath(int goal, GridPath& out);

  const GridMap& map_;
  Jumps jumps_;
  BitGrid rows_, columns_;
  JpsPlusTables tables_;
  const LandmarkHeuristic* landmarks_;
  bool use_landmarks_ = false;  // this search: landmarks given and valid for the map
  LandmarkHeuristic::Goal goal_landmarks_;
  std::uint64_t synced_version_ = ~std::uint64_t(0);
  int shift_ = 0;  // node index = y << shift_ | x
  std::vector<Node> nodes_;
  std::vector<std::uint16_t> stamps_;  // per node: generation_ + kOpen / kClosed / kBend
  JpsOpenList open_;
  std::vector<int> corners_;  // tracePath's jump points, kept to avoid allocating per query
  std::uint16_t generation_ = 0;
  int goal_x_ = 0, goal_y_ = 0, goal_idx_ = 0;
  SearchStats stats_;
};

}  // namespace zonesim::ai
